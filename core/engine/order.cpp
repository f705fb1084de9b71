// Insertion orders. BRIO (Amenta, Choi, Rote): rounds of geometrically growing size drawn at
// random, each round sorted along a Hilbert curve, so that consecutive points are close (short
// walks) while the rounds keep the expected-case guarantees of a random order. The curve's grid
// is refined wherever points crowd, so the order stays close whatever the density.
#include "core/engine/order.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <numeric>
#include <thread>

namespace dlab {

const char* toString(OrderKind kind) { return nameIn(kOrderNames, kind).data(); }

std::optional<OrderKind> parseOrderKind(std::string_view name) {
    return parseIn(kOrderNames, name);
}

namespace {

// One level of the curve, from the coarsest down. The sub-square's digit depends on the bits
// seen through the rotation/reflection accumulated so far: 2 bits of state (bit 0 swap, bit 1
// reflect). Written without branches: a branchy version mispredicts on almost every level.
struct HilbertLevel {
    std::uint32_t digit;
    std::uint32_t state;
};

constexpr HilbertLevel hilbertLevel(std::uint32_t state, std::uint32_t xBit, std::uint32_t yBit) {
    const std::uint32_t swap = state & 1u, reflect = state >> 1;
    const std::uint32_t bx = xBit ^ reflect, by = yBit ^ reflect;
    const std::uint32_t rx = swap ? by : bx, ry = swap ? bx : by;
    const std::uint32_t turn = ry ^ 1u;  // lower-left or lower-right quadrant
    return {(3u * rx) ^ ry, (swap ^ turn) | ((reflect ^ (turn & rx)) << 1)};
}

// Four levels at once: entry [state][x nibble][y nibble] = 8 digit bits | next state << 8.
// The level loop is one long chain of dependent bit operations (it was most of the BRIO
// order's time at a million points); four table lookups give the same digits.
constexpr std::array<std::uint16_t, 4 * 256> kHilbertNibbles = [] {
    std::array<std::uint16_t, 4 * 256> table{};
    for (std::uint32_t state = 0; state < 4; ++state) {
        for (std::uint32_t x = 0; x < 16; ++x) {
            for (std::uint32_t y = 0; y < 16; ++y) {
                std::uint32_t s = state, d = 0;
                for (int i = 3; i >= 0; --i) {
                    const HilbertLevel level = hilbertLevel(s, (x >> i) & 1u, (y >> i) & 1u);
                    d = (d << 2) | level.digit;
                    s = level.state;
                }
                table[(state << 8) | (x << 4) | y] = static_cast<std::uint16_t>(d | (s << 8));
            }
        }
    }
    return table;
}();

// A digit and the state before it determine the sub-square, hence the next state.
constexpr std::array<std::uint8_t, 16> kNextState = [] {
    std::array<std::uint8_t, 16> next{};
    for (std::uint32_t state = 0; state < 4; ++state) {
        for (std::uint32_t bits = 0; bits < 4; ++bits) {
            const HilbertLevel level = hilbertLevel(state, bits >> 1, bits & 1u);
            next[(state << 2) | level.digit] = static_cast<std::uint8_t>(level.state);
        }
    }
    return next;
}();

// The first 4 * nibbles levels of the curve through (x, y), entered in `state`: digits, and the
// state the curve has in the sub-square they lead to.
struct HilbertPrefix {
    std::uint64_t index;
    std::uint32_t state;
};

HilbertPrefix hilbertNibbles(std::uint32_t x, std::uint32_t y, std::uint32_t state, int nibbles) {
    std::uint64_t d = 0;
    for (int i = 4 * (nibbles - 1); i >= 0; i -= 4) {
        const std::uint32_t e =
            kHilbertNibbles[(state << 8) | (((x >> i) & 15u) << 4) | ((y >> i) & 15u)];
        d = (d << 8) | (e & 0xFFu);
        state = e >> 8;
    }
    return {d, state};
}

std::uint32_t stateAfter(std::uint32_t state, std::uint64_t index, int levels) {
    for (int i = 2 * (levels - 1); i >= 0; i -= 2)
        state = kNextState[(state << 2) | ((index >> i) & 3u)];
    return state;
}

}  // namespace

std::uint32_t hilbertStateAfter(std::uint32_t state, std::uint32_t index, int levels) {
    return stateAfter(state, index, levels);
}

std::uint32_t hilbertIndex16(std::uint32_t x, std::uint32_t y, std::uint32_t state) {
    return static_cast<std::uint32_t>(hilbertNibbles(x, y, state, 4).index);
}

std::uint32_t hilbertIndex(std::uint32_t x, std::uint32_t y, int bits) {
    std::uint32_t state = 0, d = 0;
    for (int i = bits - 1; i >= 0; --i) {
        const HilbertLevel level = hilbertLevel(state, (x >> i) & 1u, (y >> i) & 1u);
        d = (d << 2) | level.digit;
        state = level.state;
    }
    return d;
}

namespace {

void shuffle(std::vector<std::int32_t>& v, SplitMix64& rng) {
    for (std::size_t i = v.size(); i > 1; --i) {
        const std::size_t j = rng.below(static_cast<std::uint32_t>(i));
        std::swap(v[i - 1], v[j]);
    }
}

// Records (key << 32 | index): sorted by key, ties by index. Sorts are stable and the records
// are made in increasing index, so equal keys keep the input order.
using Record = std::uint64_t;
constexpr std::uint32_t keyOf(Record r) { return static_cast<std::uint32_t>(r >> 32); }
constexpr std::int32_t indexOf(Record r) { return static_cast<std::int32_t>(r & 0xFFFFFFFFu); }

// Stable LSD radix sort of records by their upper 32 bits, in three passes of 11, 11 and 10
// bits. Three passes over 2048 buckets beat two over 65536: those scatter into more open cache
// lines than the L2 holds.
constexpr int kRadixBits = 11;
constexpr std::uint32_t kRadixMask = (1u << kRadixBits) - 1;
using RadixCounts = std::array<std::array<std::uint32_t, 1u << kRadixBits>, 3>;

std::uint32_t radixDigit(Record r, int pass) {
    return static_cast<std::uint32_t>(r >> (32 + kRadixBits * pass)) & kRadixMask;
}

void countDigits(Record r, RadixCounts& count) {
    for (int pass = 0; pass < 3; ++pass) ++count[pass][radixDigit(r, pass)];
}

// The work of a pass over n items cut into `chunks` (1 or 2) consecutive ranges: work(c, begin,
// end) for each, the second range on a thread of its own.
template <class Work>
void forChunks(int chunks, std::size_t n, const Work& work) {
    if (chunks < 2) {
        work(0, std::size_t{0}, n);
        return;
    }
    std::thread second([&] { work(1, n / 2, n); });
    work(0, std::size_t{0}, n / 2);
    second.join();
}

// count[c] holds the digit histograms of chunk c of rec, of all three passes when there is one
// chunk (a pass only moves records within the array), of the first pass otherwise (the others
// are counted before their pass). Chunk c's records go after chunk c - 1's in each bucket, so the
// result is the one-chunk sort's.
void radixSort(std::vector<Record>& rec, std::array<RadixCounts, 2>& count, int chunks) {
    std::vector<Record> tmp(rec.size());
    std::vector<Record>* from = &rec;
    std::vector<Record>* to = &tmp;
    for (int pass = 0; pass < 3; ++pass) {
        if (pass > 0 && chunks > 1) {
            forChunks(chunks, rec.size(), [&](int c, std::size_t b, std::size_t e) {
                count[c][pass].fill(0);
                for (std::size_t i = b; i < e; ++i) ++count[c][pass][radixDigit((*from)[i], pass)];
            });
        }
        std::uint32_t sum = 0;  // each chunk's first slot in each bucket
        for (std::uint32_t d = 0; d <= kRadixMask; ++d) {
            for (int c = 0; c < chunks; ++c) {
                const std::uint32_t k = count[c][pass][d];
                count[c][pass][d] = sum;
                sum += k;
            }
        }
        forChunks(chunks, rec.size(), [&](int c, std::size_t b, std::size_t e) {
            auto& next = count[c][pass];
            for (std::size_t i = b; i < e; ++i) {
                const Record r = (*from)[i];
                (*to)[next[radixDigit(r, pass)]++] = r;
            }
        });
        std::swap(from, to);
    }
    if (from != &rec) rec.swap(tmp);
}

// A box mapped onto a 2^32 x 2^32 grid, each axis on its own (a flat set still fills the grid).
// Spans are differences of halves, so they cannot overflow near the largest doubles; the scale
// is capped, so a subnormal span cannot make it inf (0 * inf is a NaN cell).
class CellGrid {
public:
    CellGrid(Vec2 lo, Vec2 hi)
        : m_loX(lo.x / 2),
          m_loY(lo.y / 2),
          m_sx(scale(hi.x / 2 - m_loX)),
          m_sy(scale(hi.y / 2 - m_loY)) {}

    // The grid over the bounding box of points[id(i)] for i in [0, m).
    template <class Id>
    static CellGrid around(const std::vector<Vec2>& points, const Id& id, std::size_t m) {
        Vec2 lo = points[id(0)], hi = lo;
        for (std::size_t i = 1; i < m; ++i) {
            const Vec2 p = points[id(i)];
            lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
            hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
        }
        return {lo, hi};
    }

    struct Cell {
        std::uint32_t x, y;
    };
    Cell cellOf(Vec2 p) const {  // below 2^32 a double holds the integer part exactly
        return {static_cast<std::uint32_t>(std::clamp((p.x / 2 - m_loX) * m_sx, 0.0, kCells)),
                static_cast<std::uint32_t>(std::clamp((p.y / 2 - m_loY) * m_sy, 0.0, kCells))};
    }

private:
    static constexpr double kCells = 4294967295.0;  // 2^32 - 1
    static double scale(double halfSpan) {
        return halfSpan > 0 ? std::min(kCells / halfSpan, std::numeric_limits<double>::max()) : 0.0;
    }
    double m_loX, m_loY, m_sx, m_sy;
};

// BRIO's first sort keys each point by its cell on a 2^14 x 2^14 grid (the top 14 levels of the
// curve through the 2^32 grid: a 28-bit key, three radix passes) and keeps the next 16 levels'
// cell for points that turn out to crowd a cell.
constexpr int kTopLevels = 14;
constexpr int kFineLevels = 16;
constexpr int kBoxLevels = 16;  // of the curve through a grid around a crowd's points
std::uint32_t topKey(CellGrid::Cell c) {
    constexpr int kDrop = 32 - kTopLevels;
    return hilbertIndex16((c.x >> kDrop) << 2, (c.y >> kDrop) << 2, 0) >> 4;
}
std::uint32_t fineCell(CellGrid::Cell c) {
    constexpr int kDrop = 32 - kTopLevels - kFineLevels;
    return ((c.x >> kDrop) & 0xFFFFu) << 16 | ((c.y >> kDrop) & 0xFFFFu);
}

// A cell of the curve holding more points than this is split further: its points would keep
// their input order, and a walk from one to the next crosses every triangle in between.
constexpr std::size_t kMaxPerCell = 8;
// At most this many levels of the curve (4^6 = 4096 sub-cells) in one counting pass: the
// counts stay in the L1 cache.
constexpr int kMaxLevelsPerPass = 6;
// Gathers read this many points ahead: the reads are random, and waiting for each in turn
// costs more than the rest of the refinement.
constexpr std::size_t kAhead = 16;

// Sorts the points of a crowded cell of the first grid along the curve inside it. A cell is
// split into 4^L sub-cells at once (one stable counting pass; L levels, enough for its count)
// until each holds at most kMaxPerCell points. When a cell's levels are used up (the 16 fine
// levels first), its points go on on a 2^16 grid over the bounding box of their own points,
// entered as the curve enters the cell: the curve stays continuous, and each step shrinks the
// box by 2^16 per axis, so a few steps part points of any density. Only crowded points are read
// again, once per step.
class CellRefiner {
public:
    explicit CellRefiner(const std::vector<Vec2>& points) : m_points(points) {}

    // items[0, m): the points of one cell of the first grid, keyed on the fine grid inside it,
    // the curve entering the cell in `state`.
    void sortCell(Record* items, std::size_t m, std::uint32_t state) {
        m_items = items;
        m_work.push_back({0, m, 0, kFineLevels, state, false});
        while (!m_work.empty()) {
            const Span span = m_work.back();
            m_work.pop_back();
            if (span.end - span.begin <= kMaxPerCell) {
                finish(span);
                continue;
            }
            if (span.depth < span.levels)
                split(span);
            else
                descend(span);
        }
    }

private:
    using Item = Record;  // (key << 32 | id): the position on the curve through the span's grid
    // m_items[begin, end): points whose keys (of `levels` levels, for the curve entering the
    // grid's cell in `state`) share the first `depth` levels. `boxed`: the grid was made around
    // exactly these points.
    struct Span {
        std::size_t begin, end;
        int depth, levels;
        std::uint32_t state;
        bool boxed;
    };

    // One stable counting pass over the next L levels; sub-cells still crowded are pushed.
    void split(const Span& span) {
        const std::size_t m = span.end - span.begin;
        int levels = 1;
        while (levels < kMaxLevelsPerPass && span.depth + levels < span.levels &&
               (std::size_t{1} << (2 * levels)) * kMaxPerCell < 2 * m)
            ++levels;
        const int shift = 2 * (span.levels - span.depth - levels);
        const std::uint32_t buckets = 1u << (2 * levels);
        const auto digit = [&](Item it) { return (keyOf(it) >> shift) & (buckets - 1); };
        Item* items = m_items + span.begin;
        m_start.assign(buckets + 1, 0);
        for (std::size_t i = 0; i < m; ++i) ++m_start[digit(items[i]) + 1];
        for (std::uint32_t d = 0; d < buckets; ++d) m_start[d + 1] += m_start[d];
        m_next.assign(m_start.begin(), m_start.end() - 1);
        m_tmp.resize(m);
        for (std::size_t i = 0; i < m; ++i) m_tmp[m_next[digit(items[i])]++] = items[i];
        std::copy(m_tmp.begin(), m_tmp.begin() + static_cast<std::ptrdiff_t>(m), items);
        for (std::uint32_t d = 0; d < buckets; ++d) {
            Span sub = span;
            sub.begin = span.begin + m_start[d];
            sub.end = span.begin + m_start[d + 1];
            sub.depth = span.depth + levels;
            sub.boxed = span.boxed && sub.end - sub.begin == m;
            if (sub.end - sub.begin > kMaxPerCell)
                m_work.push_back(sub);
            else
                finish(sub);
        }
    }

    // A few points: in the order of their keys (the grid's full precision), ties by input index.
    void finish(const Span& span) {
        if (span.end - span.begin > 1) std::sort(m_items + span.begin, m_items + span.end);
    }

    // The span is one cell of its grid: key its points on a grid around them, in that cell.
    void descend(const Span& span) {
        // One cell of a grid around exactly these points: they are equal, or too close for the
        // grid's arithmetic to part. They stay as they are.
        if (span.boxed) return;
        const std::size_t m = span.end - span.begin;
        Item* items = m_items + span.begin;
        const std::uint32_t inner = stateAfter(span.state, keyOf(items[0]), span.levels);
        m_gathered.resize(m);
        for (std::size_t i = 0; i < m; ++i) {
            if (i + kAhead < m) __builtin_prefetch(&m_points[indexOf(items[i + kAhead])]);
            m_gathered[i] = m_points[indexOf(items[i])];
        }
        const CellGrid grid = CellGrid::around(
            m_gathered, [](std::size_t i) { return i; }, m);
        for (std::size_t i = 0; i < m; ++i) {
            const CellGrid::Cell c = grid.cellOf(m_gathered[i]);
            items[i] = Record{hilbertIndex16(c.x >> 16, c.y >> 16, inner)} << 32 |
                       static_cast<std::uint32_t>(indexOf(items[i]));
        }
        m_work.push_back({span.begin, span.end, 0, kBoxLevels, inner, true});
    }

    const std::vector<Vec2>& m_points;
    Item* m_items = nullptr;
    std::vector<Item> m_tmp;
    std::vector<Vec2> m_gathered;
    std::vector<std::uint32_t> m_start, m_next;
    std::vector<Span> m_work;
};

// Each point draws its round: the last round (15) with probability 7/8, the one before with
// 7/64, ..., round 0 takes the rest: each round is 8 times the size of the one before. Rounds
// that grow by 2 (Amenta, Choi and Rote's choice) break the curve into more pieces: at a million
// points the walks took 3.1 steps a point against 2.3, and the runs of every distribution were
// 8 to 12% slower; one round (the curve alone) flips more and is slower still. The records' key
// is (round, cell on the first grid), so one radix sort over the points in input order (no
// random gathers, which cost more than everything else at a million points) gives the order
// wherever that grid parts the points. fine[i] gets point i's cell on the grid inside its cell.
constexpr int kRoundGrowthBits = 3;  // each round 2^3 times the one before
std::vector<Record> sortByRoundAndCell(const std::vector<Vec2>& points, SplitMix64& rng,
                                       std::vector<std::uint32_t>& fine, int chunks) {
    const std::size_t n = points.size();
    std::array<std::pair<Vec2, Vec2>, 2> box;  // each chunk's bounding box
    forChunks(chunks, n, [&](int c, std::size_t b, std::size_t e) {
        Vec2 l = points[b], h = l;
        for (std::size_t i = b + 1; i < e; ++i) {
            l = {std::min(l.x, points[i].x), std::min(l.y, points[i].y)};
            h = {std::max(h.x, points[i].x), std::max(h.y, points[i].y)};
        }
        box[c] = {l, h};
    });
    Vec2 lo = box[0].first, hi = box[0].second;
    for (int c = 1; c < chunks; ++c) {
        lo = {std::min(lo.x, box[c].first.x), std::min(lo.y, box[c].first.y)};
        hi = {std::max(hi.x, box[c].second.x), std::max(hi.y, box[c].second.y)};
    }
    const CellGrid grid(lo, hi);
    std::vector<Record> rec(n);
    std::array<RadixCounts, 2> count{};
    forChunks(chunks, n, [&](int c, std::size_t b, std::size_t e) {
        SplitMix64 draws = rng;  // point i draws the generator's i-th number, in every chunk
        draws.discard(b);
        for (std::size_t i = b; i < e; ++i) {
            const std::uint64_t r = draws.next();
            const int zeros = r == 0 ? 64 : std::countr_zero(r);
            const std::uint32_t round =
                15u - static_cast<std::uint32_t>(std::min(zeros / kRoundGrowthBits, 15));
            const CellGrid::Cell cell = grid.cellOf(points[i]);
            fine[i] = fineCell(cell);
            rec[i] = Record{(round << 28) | topKey(cell)} << 32 | static_cast<std::uint32_t>(i);
            countDigits(rec[i], count[c]);
        }
    });
    rng.discard(n);
    radixSort(rec, count, chunks);
    return rec;
}

// Points that share a cell of the first grid (in one round) are keyed again on the fine grid
// inside it and sorted there, rec[begin, end) holding whole cells. The reads of fine[] are
// random: the loop reads ahead across cells.
void sortSharedCells(const std::vector<Vec2>& points, const std::vector<std::uint32_t>& fine,
                     std::vector<Record>& rec, std::size_t begin, std::size_t end) {
    CellRefiner refiner(points);
    for (std::size_t i = begin, j = begin; i < end; i = j) {
        const std::uint32_t key = keyOf(rec[i]);
        for (j = i + 1; j < end && keyOf(rec[j]) == key; ++j) {}
        if (j - i == 1) continue;
        // (the round's bits above the cell's do not change the curve's state)
        const std::uint32_t state = stateAfter(0, key & 0x0FFFFFFFu, kTopLevels);
        for (std::size_t k = i; k < j; ++k) {
            if (k + kAhead < end) __builtin_prefetch(&fine[indexOf(rec[k + kAhead])]);
            const std::int32_t id = indexOf(rec[k]);
            const std::uint32_t f = fine[id];
            rec[k] = Record{hilbertIndex16(f >> 16, f & 0xFFFFu, state)} << 32 |
                     static_cast<std::uint32_t>(id);
        }
        refiner.sortCell(rec.data() + i, j - i, state);
    }
}

// Below this many points a second thread costs more than it saves.
constexpr std::size_t kTwoThreadsFrom = std::size_t{1} << 16;

// With two threads each pass is cut in two, the refinement at a cell boundary near the middle:
// the same order as one thread's.
std::vector<std::int32_t> brio(const std::vector<Vec2>& points, SplitMix64& rng, int threads) {
    const std::size_t n = points.size();
    std::vector<std::int32_t> order(n);
    if (n < 64) {
        std::iota(order.begin(), order.end(), 0);
        shuffle(order, rng);
        return order;
    }
    const int chunks = threads > 1 && n >= kTwoThreadsFrom ? 2 : 1;
    std::vector<std::uint32_t> fine(n);
    std::vector<Record> rec = sortByRoundAndCell(points, rng, fine, chunks);
    std::size_t middle = chunks > 1 ? n / 2 : n;
    while (middle < n && keyOf(rec[middle]) == keyOf(rec[middle - 1])) ++middle;
    const std::array<std::size_t, 3> cut{0, middle, n};
    forChunks(chunks, n, [&](int c, std::size_t, std::size_t) {
        sortSharedCells(points, fine, rec, cut[c], cut[c + 1]);
        for (std::size_t i = cut[c]; i < cut[c + 1]; ++i) order[i] = indexOf(rec[i]);
    });
    return order;
}

}  // namespace

std::vector<std::int32_t> insertionOrder(const std::vector<Vec2>& points, OrderKind kind,
                                         std::uint64_t seed, int threads) {
    SplitMix64 rng(seed);
    switch (kind) {
        case OrderKind::Input: {
            std::vector<std::int32_t> order(points.size());
            std::iota(order.begin(), order.end(), 0);
            return order;
        }
        case OrderKind::Random: {
            std::vector<std::int32_t> order(points.size());
            std::iota(order.begin(), order.end(), 0);
            shuffle(order, rng);
            return order;
        }
        case OrderKind::Brio: return brio(points, rng, threads);
    }
    return {};
}

}  // namespace dlab
