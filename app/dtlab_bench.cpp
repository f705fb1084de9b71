// dtlab bench: times the triangulation only (not I/O), after warm-up runs; median of repeats.
#include "app/dtlab_common.h"

#include "core/engine/predicates.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <iostream>

namespace dlab::cli {

namespace {

struct BenchArgs {
    std::string input;
    int repeat = 5;
    int warmup = 1;
    bool json = false;
    int threads = 2;
    EngineFlags engine;
};

// What the timed runs measured: their times (sorted) and the last run's counts.
struct BenchResult {
    std::vector<double> ms;
    double median = 0;
    InsertStats stats;
    std::int32_t triangles = 0;
    bool twoCores = false;   // the runs took the two-core path
    std::string oneCoreWhy;  // with --threads 2, why they did not
    LocatorStats locStats;
    // Calls past the floating-point filter, by the stage that decided them (one run).
    std::int64_t orientStage[kNumPredicateTiers] = {}, incircleStage[kNumPredicateTiers] = {};
    double hitRate() const {
        return locStats.queries ? static_cast<double>(locStats.hits) / locStats.queries : 0.0;
    }
};

// Which stage decided the predicates the filter could not: every run is the same, so a run's
// share of the counters is their growth divided by the runs.
void countStages(BenchResult& res, const PredicateCounters& before, int runs) {
    const PredicateCounters& counters = predicateCounters();
    auto perRun = [&](std::uint64_t now, std::uint64_t was) {
        return static_cast<std::int64_t>((now - was) / static_cast<std::uint64_t>(runs));
    };
    for (int t = 0; t < kNumPredicateTiers; ++t) {
        res.orientStage[t] = perRun(counters.orientByTier[t], before.orientByTier[t]);
        res.incircleStage[t] = perRun(counters.incircleByTier[t], before.incircleByTier[t]);
    }
}

BenchResult timeRuns(const BenchArgs& args, const std::vector<Vec2>& points) {
    BenchResult res;
    const PredicateCounters countersBefore = predicateCounters();
    for (int r = 0; r < args.warmup + args.repeat; ++r) {  // the first `warmup` runs are not timed
        std::vector<Vec2> pts = points;                    // copied outside the timed region
        const auto t0 = std::chrono::steady_clock::now();
        if (args.threads == 2) {
            if (auto joined = triangulateOnTwoCores(pts, args.engine.options(), &res.oneCoreWhy)) {
                const auto t1 = std::chrono::steady_clock::now();
                if (r >= args.warmup)
                    res.ms.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
                res.stats = joined->stats;
                res.locStats = joined->locatorStats;
                res.triangles = joined->mesh.numTriangles();
                res.twoCores = true;
                continue;
            }
        }
        // GL locators need a context; with --threads 2 the order's sorts use both cores
        const auto made = args.engine.makeInserter(std::move(pts), args.threads);
        Inserter& ins = *made;
        ins.run();
        const auto t1 = std::chrono::steady_clock::now();
        if (r >= args.warmup)
            res.ms.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
        res.stats = ins.stats();
        res.triangles = ins.mesh().numTriangles();
        res.locStats = ins.locator()->stats();
    }
    countStages(res, countersBefore, args.warmup + args.repeat);
    std::vector<double>& ms = res.ms;
    std::sort(ms.begin(), ms.end());
    res.median =
        ms.size() % 2 ? ms[ms.size() / 2] : (ms[ms.size() / 2 - 1] + ms[ms.size() / 2]) / 2;
    return res;
}

void printBenchJson(const BenchArgs& args, std::size_t n, const BenchResult& res) {
    const auto pn = static_cast<double>(n);
    const InsertStats& stats = res.stats;
    nlohmann::ordered_json j;
    j["tool"] = "dtlab";
    j["input"] = args.input;
    j["n"] = n;
    j["locate"] = args.engine.locate;
    j["order"] = args.engine.order;
    j["boundary"] = args.engine.boundary;
    j["threads"] = res.twoCores ? 2 : 1;
    if (!res.oneCoreWhy.empty()) j["one_core_because"] = res.oneCoreWhy;
    j["repeat"] = args.repeat;
    j["warmup"] = args.warmup;
    j["median_ms"] = res.median;
    j["min_ms"] = res.ms.front();
    j["max_ms"] = res.ms.back();
    j["ns_per_point"] = res.median * 1e6 / pn;
    j["flips_per_point"] = stats.flips / pn;
    j["incircle_tests_per_point"] = stats.inCircleTests / pn;
    j["walk_steps_per_point"] = stats.walkSteps / pn;
    j["locator_hit_rate"] = res.hitRate();
    j["duplicates"] = stats.duplicates;
    j["triangles"] = res.triangles;
    nlohmann::ordered_json stages;
    for (int t = 1; t < kNumPredicateTiers; ++t) {
        const char* name = toString(static_cast<PredicateTier>(t));
        stages["orient2d"][name] = res.orientStage[t];
        stages["incircle"][name] = res.incircleStage[t];
    }
    j["predicates_past_filter"] = stages;
    std::cout << j.dump() << "\n";
}

void printBenchText(const BenchArgs& args, std::size_t n, const BenchResult& res) {
    const auto pn = static_cast<double>(n);
    const InsertStats& stats = res.stats;
    std::printf("%s: n=%zu locate=%s order=%s boundary=%s threads=%d\n", args.input.c_str(), n,
                args.engine.locate.c_str(), args.engine.order.c_str(), args.engine.boundary.c_str(),
                res.twoCores ? 2 : 1);
    if (!res.oneCoreWhy.empty()) std::printf("  one core: %s\n", res.oneCoreWhy.c_str());
    std::printf("  median %.2f ms (min %.2f, max %.2f, %d runs after %d warm-up run(s))\n",
                res.median, res.ms.front(), res.ms.back(), args.repeat, args.warmup);
    std::printf(
        "  %.1f ns/point, %.3f flips/point, %.3f in-circle tests/point, %.3f walk "
        "steps/point\n",
        res.median * 1e6 / pn, stats.flips / pn, stats.inCircleTests / pn, stats.walkSteps / pn);
    std::printf("  locator hint hit rate %.3f, %lld duplicates skipped, %d triangles\n",
                res.hitRate(), static_cast<long long>(stats.duplicates), res.triangles);
    std::printf("  past the filter (one run):");
    for (int t = 1; t < kNumPredicateTiers; ++t) {
        std::printf(" %s %lld+%lld", toString(static_cast<PredicateTier>(t)),
                    static_cast<long long>(res.orientStage[t]),
                    static_cast<long long>(res.incircleStage[t]));
    }
    std::printf(" (orient2d+incircle)\n");
}

void runBench(const BenchArgs& args) {
    const LoadedPoints loaded = loadPoints(args.input);
    const std::size_t n = loaded.points.size();
    if (n == 0) fail(args.input + ": no points: there is nothing to time", 2);
    const BenchResult res = timeRuns(args, loaded.points);
    if (args.json) {
        printBenchJson(args, n, res);
    } else {
        printBenchText(args, n, res);
    }
}

}  // namespace

void addBench(CLI::App& app) {
    auto args = std::make_shared<BenchArgs>();
    CLI::App* cmd =
        app.add_subcommand("bench", "Time the triangulation of a point file (median of repeats)");
    cmd->add_option("--input,input", args->input, "Point file (.node, .csv, .xy, .pts)")
        ->required();
    cmd->add_option("--repeat", args->repeat, "Timed runs after the warm-up")
        ->check(CLI::Range(1, 1000))
        ->capture_default_str();
    cmd->add_option("--warmup", args->warmup, "Untimed runs first (0 for slow settings)")
        ->check(CLI::Range(0, 100))
        ->capture_default_str();
    cmd->add_flag("--json", args->json, "Print one JSON object");
    cmd->add_option("--threads", args->threads,
                    "As dtlab triangulate's: 2 triangulates two halves at once and joins them "
                    "(exact boundary, walk, 4096 points or more), 1 the whole set in one")
        ->check(CLI::Range(1, 2))
        ->capture_default_str();
    args->engine.add(*cmd);
    cmd->callback([args] { guarded([&] { runBench(*args); }); });
}

}  // namespace dlab::cli
