// Writers for a finished mesh: Triangle formats, OFF, OBJ and SVG.
//
// [SECTION] Text output helpers
// [SECTION] Triangle formats
// [SECTION] OFF / OBJ
// [SECTION] SVG
#include "core/engine/io_write.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <ostream>
#include <stdexcept>

namespace dlab {

//-----------------------------------------------------------------------------------------------
// [SECTION] Text output helpers
//-----------------------------------------------------------------------------------------------

namespace {

// Collects text in a string and hands it to the stream in large pieces: one os.write per 64 KiB
// instead of one formatted insertion per number.
class Buffer {
public:
    explicit Buffer(std::ostream& os) : m_os(os) { m_text.reserve(kChunk + 256); }
    std::string& text() { return m_text; }
    // Call after each record.
    void maybeFlush() {
        if (m_text.size() >= kChunk) flush();
    }
    void flush() {
        if (!m_text.empty()) m_os.write(m_text.data(), static_cast<std::streamsize>(m_text.size()));
        m_text.clear();
    }

private:
    static constexpr std::size_t kChunk = std::size_t{1} << 16;
    std::ostream& m_os;
    std::string m_text;
};

void appendInt(std::string& out, std::int64_t v) {
    char buf[24];
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    out.append(buf, r.ptr);
}

void checkBase(int indexBase, const char* who) {
    if (indexBase != 0 && indexBase != 1) {
        throw std::invalid_argument(std::string(who) + ": index base must be 0 or 1, found " +
                                    std::to_string(indexBase));
    }
}

void checkTriangles(const Mesh& m, const char* who) {
    if (m.V.size() % 3 != 0) {
        throw std::invalid_argument(std::string(who) + ": |V| = " + std::to_string(m.V.size()) +
                                    " is not a multiple of 3");
    }
}

}  // namespace

//-----------------------------------------------------------------------------------------------
// [SECTION] Triangle formats
//-----------------------------------------------------------------------------------------------

namespace {

// Appends `count` lines, each written by line(s, i) and ended here.
template <class LineFn>
void appendLines(Buffer& out, std::size_t count, LineFn&& line) {
    std::string& s = out.text();
    for (std::size_t i = 0; i < count; ++i) {
        line(s, i);
        s += '\n';
        out.maybeFlush();
    }
}

// Triangle's file shape (.node, .ele, .neigh, .v.edge): the header "<count><rest>", then one line
// per record: its number (from indexBase), then what fields(s, i) appends.
template <class FieldsFn>
void writeTriangleFormat(std::ostream& os, std::size_t count, const char* rest, int indexBase,
                         FieldsFn&& fields) {
    Buffer out(os);
    appendInt(out.text(), static_cast<std::int64_t>(count));
    out.text() += rest;
    appendLines(out, count, [&](std::string& s, std::size_t i) {
        appendInt(s, static_cast<std::int64_t>(i) + indexBase);
        fields(s, i);
    });
    out.flush();
}

// "x y", each the shortest text that reads back as the same double.
void appendXY(std::string& s, Vec2 p) {
    appendShortest(s, p.x);
    s += ' ';
    appendShortest(s, p.y);
}

// " a b c": triangle t's three vertices, numbered from base.
void appendVertices(std::string& s, const Mesh& mesh, std::int32_t t, std::int64_t base) {
    for (int i = 0; i < 3; ++i) {
        s += ' ';
        appendInt(s, static_cast<std::int64_t>(mesh.V[corner(t, i)]) + base);
    }
}

// " a b c": the triangles across triangle t's three sides, numbered from base (-1: none).
void appendNeighbours(std::string& s, const Mesh& mesh, std::int32_t t, std::int64_t base) {
    for (int i = 0; i < 3; ++i) {
        const std::int32_t o = mesh.O[corner(t, i)];
        s += ' ';
        appendInt(s, o == kNone ? -1 : static_cast<std::int64_t>(tri(o)) + base);
    }
}

// " a b" for a Voronoi edge, " a -1 dx dy" for a ray (numbered from base).
void appendVoronoiEdge(std::string& s, const VoronoiDiagram::Edge& e, std::int64_t base) {
    s += ' ';
    appendInt(s, static_cast<std::int64_t>(e.a) + base);
    if (e.isRay()) {
        s += " -1 ";
        appendXY(s, e.direction);
    } else {
        s += ' ';
        appendInt(s, static_cast<std::int64_t>(e.b) + base);
    }
}

// A .node file of points: "<#points> 2 0 0", then "<i> x y".
void writePointNode(std::ostream& os, const std::vector<Vec2>& points, int indexBase) {
    writeTriangleFormat(os, points.size(), " 2 0 0\n", indexBase,
                        [&](std::string& s, std::size_t i) {
                            s += ' ';
                            appendXY(s, points[i]);
                        });
}

std::size_t triangleCount(const Mesh& mesh) {
    return static_cast<std::size_t>(mesh.numTriangles());
}

}  // namespace

void writeNode(std::ostream& os, const std::vector<Vec2>& points, int indexBase) {
    checkBase(indexBase, "writeNode");
    writePointNode(os, points, indexBase);
}

void writeEle(std::ostream& os, const Mesh& mesh, int indexBase) {
    checkBase(indexBase, "writeEle");
    checkTriangles(mesh, "writeEle");
    writeTriangleFormat(os, triangleCount(mesh), " 3 0\n", indexBase,
                        [&](std::string& s, std::size_t t) {
                            appendVertices(s, mesh, static_cast<std::int32_t>(t), indexBase);
                        });
}

void writeNeigh(std::ostream& os, const Mesh& mesh, int indexBase) {
    checkBase(indexBase, "writeNeigh");
    checkTriangles(mesh, "writeNeigh");
    if (mesh.O.size() != mesh.V.size()) {
        throw std::invalid_argument("writeNeigh: |O| = " + std::to_string(mesh.O.size()) +
                                    " differs from |V| = " + std::to_string(mesh.V.size()));
    }
    writeTriangleFormat(os, triangleCount(mesh), " 3\n", indexBase,
                        [&](std::string& s, std::size_t t) {
                            appendNeighbours(s, mesh, static_cast<std::int32_t>(t), indexBase);
                        });
}

void writeVoronoiNode(std::ostream& os, const VoronoiDiagram& diagram, int indexBase) {
    checkBase(indexBase, "writeVoronoiNode");
    writePointNode(os, diagram.vertices, indexBase);
}

void writeVoronoiEdge(std::ostream& os, const VoronoiDiagram& diagram, int indexBase) {
    checkBase(indexBase, "writeVoronoiEdge");
    writeTriangleFormat(
        os, diagram.edges.size(), " 0\n", indexBase,
        [&](std::string& s, std::size_t i) { appendVoronoiEdge(s, diagram.edges[i], indexBase); });
}

//-----------------------------------------------------------------------------------------------
// [SECTION] OFF / OBJ
//-----------------------------------------------------------------------------------------------

namespace {

// OFF's and OBJ's header: "<before><#vertices><between><#triangles><after>".
void appendCounts(std::string& s, const Mesh& mesh, const char* before, const char* between,
                  const char* after) {
    s += before;
    appendInt(s, mesh.numVertices());
    s += between;
    appendInt(s, mesh.numTriangles());
    s += after;
}

// OFF's and OBJ's body: a line per point, "<pointLead>x y 0", then a line per triangle,
// "<faceLead> a b c" with the vertices numbered from base.
void appendPointsAndFaces(Buffer& out, const Mesh& mesh, const char* pointLead, char faceLead,
                          int base) {
    appendLines(out, mesh.G.size(), [&](std::string& s, std::size_t i) {
        s += pointLead;
        appendXY(s, mesh.G[i]);
        s += " 0";
    });
    appendLines(out, triangleCount(mesh), [&](std::string& s, std::size_t t) {
        s += faceLead;
        appendVertices(s, mesh, static_cast<std::int32_t>(t), base);
    });
}

}  // namespace

void writeOff(std::ostream& os, const Mesh& mesh) {
    checkTriangles(mesh, "writeOff");
    Buffer out(os);
    appendCounts(out.text(), mesh, "OFF\n", " ", " 0\n");
    appendPointsAndFaces(out, mesh, "", '3', 0);
    out.flush();
}

void writeObj(std::ostream& os, const Mesh& mesh) {
    checkTriangles(mesh, "writeObj");
    Buffer out(os);
    appendCounts(out.text(), mesh, "# Delaunay Lab: ", " vertices, ", " triangles\n");
    appendPointsAndFaces(out, mesh, "v ", 'f', 1);
    out.flush();
}

//-----------------------------------------------------------------------------------------------
// [SECTION] SVG
//-----------------------------------------------------------------------------------------------

std::string xmlEscape(std::string_view s) {
    std::string out;
    out.reserve(s.size());
    std::size_t i = 0;
    while (i < s.size()) {
        const auto c = static_cast<unsigned char>(s[i]);
        if (c < 0x80) {
            switch (c) {
                case '&': out += "&amp;"; break;
                case '<': out += "&lt;"; break;
                case '>': out += "&gt;"; break;
                case '"': out += "&quot;"; break;
                case '\'': out += "&apos;"; break;
                default:
                    out += (c < 0x20 && c != '\t' && c != '\n' && c != '\r') || c == 0x7f
                               ? '?'
                               : static_cast<char>(c);
            }
            ++i;
            continue;
        }
        // A well-formed UTF-8 sequence (no overlongs, no surrogates, at most U+10FFFF) is kept.
        std::size_t len = 0;
        unsigned char lo = 0x80, hi = 0xBF;
        if (c >= 0xC2 && c <= 0xDF)
            len = 2;
        else if (c == 0xE0)
            len = 3, lo = 0xA0;
        else if ((c >= 0xE1 && c <= 0xEC) || c == 0xEE || c == 0xEF)
            len = 3;
        else if (c == 0xED)
            len = 3, hi = 0x9F;
        else if (c == 0xF0)
            len = 4, lo = 0x90;
        else if (c >= 0xF1 && c <= 0xF3)
            len = 4;
        else if (c == 0xF4)
            len = 4, hi = 0x8F;
        bool ok = len > 0 && i + len <= s.size();
        for (std::size_t k = 1; ok && k < len; ++k) {
            const auto d = static_cast<unsigned char>(s[i + k]);
            ok = k == 1 ? (d >= lo && d <= hi) : (d >= 0x80 && d <= 0xBF);
        }
        // U+FFFE and U+FFFF are not XML characters either.
        if (ok && len == 3 && c == 0xEF && static_cast<unsigned char>(s[i + 1]) == 0xBF &&
            static_cast<unsigned char>(s[i + 2]) >= 0xBE) {
            ok = false;
        }
        if (ok) {
            out.append(s.substr(i, len));
            i += len;
        } else {
            out += '?';
            ++i;
        }
    }
    return out;
}

namespace {

bool isFinite(Vec2 p) { return std::isfinite(p.x) && std::isfinite(p.y); }

// Pixel coordinates: two decimals are plenty on screen; far-off values (circumcircles of needle
// triangles) switch to the exponent form, which SVG numbers allow.
void appendPx(std::string& out, double v) {
    if (v == 0.0) v = 0.0;  // no "-0.00"
    if (std::fabs(v) < 1e9) {
        appendFixed(out, v, 2);
    } else {
        appendGeneral(out, v, 9);
    }
}

// World -> pixel map. The world box is prescaled by an exact power of two so that its larger
// side lies in [1, 2): spans of 1e-300 or 1e300 (even 2 * DBL_MAX) map without overflow or
// underflow. y is flipped (world y up, SVG y down).
class PixelMap {
public:
    PixelMap(const std::vector<Vec2>& points, double width) {
        m_width = std::isfinite(width) && width >= 16.0 ? std::min(width, 1e6) : 800.0;
        m_margin = std::max(8.0, 0.04 * m_width);
        const double inner = m_width - 2 * m_margin;
        bool any = false;
        for (const Vec2& p : points) {
            if (!isFinite(p)) continue;
            if (!any) {
                m_lo = m_hi = p;
                any = true;
                continue;
            }
            m_lo.x = std::min(m_lo.x, p.x);
            m_lo.y = std::min(m_lo.y, p.y);
            m_hi.x = std::max(m_hi.x, p.x);
            m_hi.y = std::max(m_hi.y, p.y);
        }
        m_any = any;
        // The spans overflow only for coordinates near ±DBL_MAX; then halve first (exact there).
        int pre = 0;
        double sx = m_hi.x - m_lo.x, sy = m_hi.y - m_lo.y;
        if (!std::isfinite(sx) || !std::isfinite(sy)) {
            sx = m_hi.x * 0.5 - m_lo.x * 0.5;
            sy = m_hi.y * 0.5 - m_lo.y * 0.5;
            pre = 1;
        }
        const double big = std::max(sx, sy);
        double spanX = 0.0, spanY = 0.0;  // in pixels
        if (big > 0.0) {
            const int e = std::ilogb(big);  // the true larger span times 2^m_k lies in [1, 2)
            m_k = -e - pre;
            m_s = inner / std::ldexp(big, -e);
            spanX = std::ldexp(sx, -e) * m_s;
            spanY = std::ldexp(sy, -e) * m_s;
        } else {
            m_k = 0;  // one point (or none): any scale will do, the point goes to the middle
            m_s = 1.0;
        }
        const double innerHeight = std::max(spanY, 0.25 * inner);
        m_height = innerHeight + 2 * m_margin;
        m_offX = m_margin + (inner - spanX) / 2;
        m_offY = m_margin + (innerHeight - spanY) / 2;
    }

    bool any() const { return m_any; }
    double width() const { return m_width; }
    double height() const { return m_height; }
    double margin() const { return m_margin; }

    // NaN/inf in, non-finite out: callers skip those elements.
    double px(double x) const { return m_offX + scaled(x, m_lo.x) * m_s; }
    double py(double y) const { return m_offY + scaled(m_hi.y, y) * m_s; }
    Vec2 map(Vec2 p) const { return {px(p.x), py(p.y)}; }

    // The world box that the whole picture shows (margins included), clamped to finite values.
    std::pair<Vec2, Vec2> visibleBox() const {
        const double unit = std::ldexp(1.0 / m_s, -m_k);  // world units per pixel
        auto clampFinite = [](double v) {
            const double big = std::numeric_limits<double>::max();
            return std::isnan(v) ? 0.0 : std::clamp(v, -big, big);
        };
        // Computed as lo + k * unit, where k is a pixel count: fine unless unit overflows, in
        // which case the clamp keeps the box finite.
        const Vec2 lo{clampFinite(m_lo.x - m_offX * unit),
                      clampFinite(m_hi.y - (m_height - m_offY) * unit)};
        const Vec2 hi{clampFinite(m_lo.x + (m_width - m_offX) * unit),
                      clampFinite(m_hi.y + m_offY * unit)};
        return {lo, hi};
    }

private:
    // (a - b) * 2^m_k, without overflow in the subtraction. ldexp, not a multiplication by a
    // stored power of two: for subnormal spans 2^m_k itself would overflow.
    double scaled(double a, double b) const {
        const double d = a - b;
        if (std::isfinite(d)) return std::ldexp(d, m_k);
        return std::ldexp(a * 0.5 - b * 0.5, m_k + 1);
    }

    Vec2 m_lo{}, m_hi{};
    bool m_any = false;
    double m_width = 800, m_height = 800, m_margin = 32;
    int m_k = 0;
    double m_s = 1, m_offX = 0, m_offY = 0;
};

void appendPoint(std::string& s, Vec2 p) {
    appendPx(s, p.x);
    s += ',';
    appendPx(s, p.y);
}

// ` name="value"`: an attribute in pixels.
void appendAttribute(std::string& s, const char* name, double value) {
    s += ' ';
    s += name;
    s += "=\"";
    appendPx(s, value);
    s += '"';
}

void appendLine(std::string& s, Vec2 a, Vec2 b) {
    s += "<line";
    appendAttribute(s, "x1", a.x);
    appendAttribute(s, "y1", a.y);
    appendAttribute(s, "x2", b.x);
    appendAttribute(s, "y2", b.y);
    s += "/>\n";
}

void appendCircle(std::string& s, Vec2 c, double r) {
    s += "<circle";
    appendAttribute(s, "cx", c.x);
    appendAttribute(s, "cy", c.y);
    appendAttribute(s, "r", r);
    s += "/>\n";
}

// Triangle t exists and its three vertices are points of the mesh.
bool validTriangle(const Mesh& mesh, std::int32_t t) {
    if (t < 0 || t >= mesh.numTriangles()) return false;
    for (int i = 0; i < 3; ++i) {
        const std::int32_t v = mesh.V[corner(t, i)];
        if (v < 0 || v >= mesh.numVertices()) return false;
    }
    return true;
}

void appendSvgHeader(std::string& s, const PixelMap& pm, const std::string& title) {
    s += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
    s += "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\"";
    appendAttribute(s, "width", pm.width());
    appendAttribute(s, "height", pm.height());
    s += " viewBox=\"0 0 ";
    appendPx(s, pm.width());
    s += ' ';
    appendPx(s, pm.height());
    s += "\">\n";
    if (!title.empty()) s += "<title>" + title + "</title>\n";
    s += "<rect x=\"0\" y=\"0\" width=\"100%\" height=\"100%\" fill=\"#ffffff\"/>\n";
}

void appendHighlight(Buffer& out, const Mesh& mesh, const PixelMap& pm,
                     const std::vector<std::int32_t>& highlight) {
    std::string& s = out.text();
    s += "<g class=\"highlight\" fill=\"#ffd54f\" fill-opacity=\"0.7\" stroke=\"none\">\n";
    for (const std::int32_t t : highlight) {
        if (!validTriangle(mesh, t)) continue;
        const Vec2 a = pm.map(mesh.point(corner(t, 0))), b = pm.map(mesh.point(corner(t, 1))),
                   c = pm.map(mesh.point(corner(t, 2)));
        if (!isFinite(a) || !isFinite(b) || !isFinite(c)) continue;
        s += "<polygon points=\"";
        appendPoint(s, a);
        s += ' ';
        appendPoint(s, b);
        s += ' ';
        appendPoint(s, c);
        s += "\"/>\n";
        out.maybeFlush();
    }
    s += "</g>\n";
}

void appendCircumcircles(Buffer& out, const Mesh& mesh, const PixelMap& pm) {
    std::string& s = out.text();
    s += "<g class=\"circumcircles\" fill=\"none\" stroke=\"#9e9e9e\" stroke-width=\"0.75\" "
         "stroke-dasharray=\"4 3\">\n";
    for (std::int32_t t = 0; t < mesh.numTriangles(); ++t) {
        if (!validTriangle(mesh, t)) continue;
        const Vec2 a = mesh.point(corner(t, 0));
        const Vec2 cc = circumcenter(a, mesh.point(corner(t, 1)), mesh.point(corner(t, 2)));
        const Vec2 pc = pm.map(cc), pa = pm.map(a);
        const double r = std::hypot(pc.x - pa.x, pc.y - pa.y);
        if (!isFinite(pc) || !std::isfinite(r)) continue;
        appendCircle(s, pc, r);
        out.maybeFlush();
    }
    s += "</g>\n";
}

// The Voronoi edges clipped to the picture (the mesh has its O table).
void appendVoronoi(Buffer& out, const Mesh& mesh, const PixelMap& pm) {
    std::string& s = out.text();
    const VoronoiDiagram vd = buildVoronoi(mesh);
    const auto [lo, hi] = pm.visibleBox();
    s += "<g class=\"voronoi\" stroke=\"#d32f2f\" stroke-width=\"1.25\" "
         "stroke-linecap=\"round\">\n";
    for (const auto& [a, b] : clippedSegments(vd, lo, hi)) {
        const Vec2 pa = pm.map(a), pb = pm.map(b);
        if (!isFinite(pa) || !isFinite(pb)) continue;
        appendLine(s, pa, pb);
        out.maybeFlush();
    }
    s += "</g>\n";
}

// One line per edge: from the corner table when O is there, else per triangle side.
void appendMeshEdges(Buffer& out, const Mesh& mesh, const PixelMap& pm) {
    std::string& s = out.text();
    s += "<g class=\"mesh\" stroke=\"#1565c0\" stroke-width=\"1\" stroke-linecap=\"round\">\n";
    auto edge = [&](std::int32_t c) {
        if (!validTriangle(mesh, tri(c))) return;
        const Vec2 a = pm.map(mesh.point(next(c))), b = pm.map(mesh.point(prev(c)));
        if (!isFinite(a) || !isFinite(b)) return;
        appendLine(s, a, b);
        out.maybeFlush();
    };
    if (mesh.O.size() == mesh.V.size()) {
        forEachEdge(mesh, edge);
    } else {
        for (std::int32_t c = 0; c < mesh.numCorners(); ++c) edge(c);
    }
    s += "</g>\n";
}

// The points as dots, smaller the more there are.
void appendPoints(Buffer& out, const Mesh& mesh, const PixelMap& pm) {
    std::string& s = out.text();
    const std::size_t n = mesh.G.size();
    const double r = n <= 200 ? 3.0 : n <= 5000 ? 1.75 : 0.9;
    s += "<g class=\"points\" fill=\"#212121\" stroke=\"none\">\n";
    for (const Vec2& p : mesh.G) {
        const Vec2 q = pm.map(p);
        if (!isFinite(q)) continue;
        appendCircle(s, q, r);
        out.maybeFlush();
    }
    s += "</g>\n";
}

// The title as text in the top margin (already escaped).
void appendTitle(std::string& s, const PixelMap& pm, const std::string& title) {
    s += "<text";
    appendAttribute(s, "x", pm.margin() / 2);
    appendAttribute(s, "y", pm.margin() * 0.6);
    s += " font-family=\"sans-serif\"";
    appendAttribute(s, "font-size", std::clamp(pm.margin() * 0.45, 8.0, 18.0));
    s += " fill=\"#424242\">" + title + "</text>\n";
}

}  // namespace

// The layers bottom to top: highlighted triangles, circumcircles, Voronoi edges, mesh edges,
// points, then the title.
void writeSvg(std::ostream& os, const Mesh& mesh, const SvgOptions& options) {
    checkTriangles(mesh, "writeSvg");
    const PixelMap pm(mesh.G, options.width);
    const bool any = mesh.numTriangles() > 0;
    Buffer out(os);
    const std::string title = xmlEscape(options.title);
    appendSvgHeader(out.text(), pm, title);
    if (!options.highlight.empty()) appendHighlight(out, mesh, pm, options.highlight);
    if (options.circumcircles && any) appendCircumcircles(out, mesh, pm);
    if (options.voronoi && any && mesh.O.size() == mesh.V.size()) appendVoronoi(out, mesh, pm);
    if (options.mesh && any) appendMeshEdges(out, mesh, pm);
    if (options.points && pm.any()) appendPoints(out, mesh, pm);
    if (!title.empty()) appendTitle(out.text(), pm, title);
    out.text() += "</svg>\n";
    out.flush();
}

}  // namespace dlab
