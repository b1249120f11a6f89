// ObjScan: encoding checks and a line-by-line validation of OBJ text that mirrors tinyobjloader's tokenizer.
#include "Resources/ObjScan.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>

namespace sr {

namespace {

// Lines are split exactly as tinyobjloader's safeGetline does: at LF, CR, or CR LF.
class LineCursor {
public:
    explicit LineCursor(TextSpan t) : p_(t.begin), end_(t.end) {}
    bool next(const char*& b, const char*& e) {
        if (p_ >= end_) return false;
        b = p_;
        while (p_ < end_ && *p_ != '\n' && *p_ != '\r') ++p_;
        e = p_;
        if (p_ < end_) {
            if (*p_ == '\r' && p_ + 1 < end_ && p_[1] == '\n') ++p_;
            ++p_;
        }
        ++line_;
        return true;
    }
    std::size_t line() const { return line_; }

private:
    const char* p_;
    const char* end_;
    std::size_t line_ = 0;
};

bool isBlank(char c) { return c == ' ' || c == '\t'; }

const char* skipBlanks(const char* p, const char* e) {
    while (p < e && isBlank(*p)) ++p;
    return p;
}

// What kind of OBJ statement a (blank-skipped) line is, decided as tinyobjloader decides it.
enum class Kind { Other, Position, Normal, TexCoord, Weight, Face, LineOrPoint, Group, UseMtl /* or mtllib */ };

Kind kindOf(const char* p, const char* e) {
    const auto at = [&](std::size_t i) { return p + i < e ? p[i] : '\0'; };
    if (at(0) == 'v') {
        if (isBlank(at(1))) return Kind::Position;
        if (at(1) == 'n' && isBlank(at(2))) return Kind::Normal;
        if (at(1) == 't' && isBlank(at(2))) return Kind::TexCoord;
        if (at(1) == 'w' && isBlank(at(2))) return Kind::Weight;
        return Kind::Other;
    }
    if (at(0) == 'f' && isBlank(at(1))) return Kind::Face;
    if ((at(0) == 'l' || at(0) == 'p') && isBlank(at(1))) return Kind::LineOrPoint;
    if ((at(0) == 'g' || at(0) == 'o') && isBlank(at(1))) return Kind::Group;
    if (e - p >= 6 && (std::memcmp(p, "usemtl", 6) == 0 || std::memcmp(p, "mtllib", 6) == 0)) return Kind::UseMtl;
    return Kind::Other;
}

std::string quoted(const char* b, const char* e) {
    const std::size_t n = std::size_t(e - b);
    return "'" + std::string(b, std::min<std::size_t>(n, 40)) + (n > 40 ? "...'" : "'");
}

// True when tinyobjloader's tryParseDouble accepts the token (else it silently uses 0), and the
// token is not a decimal comma ("0,5") or an MSVC non-finite spelling ("1.#INF", "-1.#IND"),
// which it would misread as a plain number. Trailing junk after a number is tolerated, as there.
// *exponent (when given) receives the token's decimal exponent (0 without one).
bool isAcceptedNumber(const char* b, const char* e, long* exponentOut = nullptr) {
    if (exponentOut) *exponentOut = 0;
    for (const char* q = b; q < e; ++q)
        if (*q == '#' || *q == ',') return false;
    const auto digit = [](char c) { return c >= '0' && c <= '9'; };
    const char* p = b;
    if (p < e && (*p == '+' || *p == '-')) ++p;
    if (p >= e || !(digit(*p) || *p == '.')) return false;
    while (p < e && digit(*p)) ++p;
    if (p < e && *p == '.') {
        ++p;
        while (p < e && digit(*p)) ++p;
    }
    if (p >= e || (*p != 'e' && *p != 'E')) return true;
    ++p;
    const bool negative = p < e && *p == '-';
    if (p < e && (*p == '+' || *p == '-')) ++p;
    std::size_t expDigits = 0;
    long exponent = 0;
    while (p < e && digit(*p)) {
        if (exponent > 2147483647L / 10) return false; // tinyobjloader fails on exponent overflow
        exponent = exponent * 10 + (*p++ - '0');
        ++expDigits;
    }
    if (exponentOut) *exponentOut = negative ? -exponent : exponent;
    return expDigits > 0;
}

// atoi() as parseTriple calls it (leading white space, sign, digits), saturated instead of
// overflowing: any magnitude above 2^31 is reported as out of range anyway.
long long safeAtoi(const char* p, const char* e) {
    while (p < e && (isBlank(*p) || *p == '\v' || *p == '\f')) ++p;
    bool neg = false;
    if (p < e && (*p == '+' || *p == '-')) neg = (*p++ == '-');
    long long v = 0;
    while (p < e && *p >= '0' && *p <= '9') {
        v = std::min<long long>(v * 10 + (*p - '0'), 1LL << 40);
        ++p;
    }
    return neg ? -v : v;
}

const char* skipToSeparator(const char* p, const char* e) { // strcspn(p, "/ \t\r")
    while (p < e && *p != '/' && !isBlank(*p)) ++p;
    return p;
}

struct IndexCheck {
    const std::string& name;
    std::size_t line;
    std::string error;

    // One index of kind `what` (vertex/normal/texture coordinate) with `count` entries defined so far.
    bool check(long long idx, std::size_t count, const char* what, const char* tb, const char* te) {
        if (idx != 0 && (idx > 0 ? std::size_t(idx) <= count : std::size_t(-idx) <= count)) return true;
        const std::string where = name + ":" + std::to_string(line) + ": face vertex " + quoted(tb, te) + ": ";
        if (idx == 0) {
            error = where + what + " index 0 is invalid (OBJ indices start at 1)";
        } else if (idx > 0 && std::size_t(idx) > count) {
            error = where + what + " index " + std::to_string(idx) + " is out of range (only " +
                    std::to_string(count) + " defined before this line)";
        } else {
            error = where + "relative " + what + " index " + std::to_string(idx) +
                    " points before the first one (only " + std::to_string(count) + " defined before this line)";
        }
        return false;
    }
};

// Validates one face-vertex starting at p, mirroring tinyobjloader's parseTriple (i, i/j, i//k,
// i/j/k). Returns the position after it, or nullptr with ic.error set.
const char* checkTriple(const char* p, const char* e, const ObjScanStats& s, IndexCheck& ic) {
    const char* tb = p;
    const char* te = p;
    while (te < e && !isBlank(*te)) ++te;
    if (!ic.check(safeAtoi(p, e), s.positions, "vertex", tb, te)) return nullptr;
    p = skipToSeparator(p, e);
    if (p >= e || *p != '/') return p;
    ++p;
    if (p < e && *p == '/') {
        ++p;
        if (!ic.check(safeAtoi(p, e), s.normals, "normal", tb, te)) return nullptr;
        return skipToSeparator(p, e);
    }
    if (!ic.check(safeAtoi(p, e), s.texcoords, "texture coordinate", tb, te)) return nullptr;
    p = skipToSeparator(p, e);
    if (p >= e || *p != '/') return p;
    ++p;
    if (!ic.check(safeAtoi(p, e), s.normals, "normal", tb, te)) return nullptr;
    return skipToSeparator(p, e);
}

// Number of blank-separated tokens in [p, e).
std::size_t countTokens(const char* p, const char* e) {
    std::size_t n = 0;
    while ((p = skipBlanks(p, e)) < e) {
        ++n;
        while (p < e && !isBlank(*p)) ++p;
    }
    return n;
}

} // namespace

Result<TextSpan> checkText(const unsigned char* data, std::size_t size, const std::string& name) {
    using R = Result<TextSpan>;
    if (size >= 2 && ((data[0] == 0xFF && data[1] == 0xFE) || (data[0] == 0xFE && data[1] == 0xFF))) {
        return R::failure(name + ": UTF-16 text is not supported, save as UTF-8");
    }
    if (size >= 8 && std::memcmp(data, "\x89PNG\r\n\x1a\n", 8) == 0)
        return R::failure(name + ": this is a PNG image, not a text file");
    if (size >= 3 && data[0] == 0xFF && data[1] == 0xD8 && data[2] == 0xFF)
        return R::failure(name + ": this is a JPEG image, not a text file");
    std::size_t offset = 0;
    if (size >= 3 && data[0] == 0xEF && data[1] == 0xBB && data[2] == 0xBF) offset = 3; // UTF-8 BOM
    for (std::size_t i = offset; i < size; ++i) {
        const unsigned char c = data[i];
        if (c >= 0x20 || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f' || c == 0x1A) continue;
        // UTF-16 without a BOM: ASCII text with a NUL beside every character.
        if (c == 0 && size >= 4) {
            const std::size_t n = std::min<std::size_t>(size & ~std::size_t(1), 512);
            std::size_t evenNul = 0, oddNul = 0;
            for (std::size_t k = 0; k < n; ++k)
                if (data[k] == 0) ++(k % 2 ? oddNul : evenNul);
            if (std::max(evenNul, oddNul) * 4 >= n && std::min(evenNul, oddNul) * 8 < n)
                return R::failure(name + ": UTF-16 text is not supported, save as UTF-8");
        }
        const std::size_t line = 1 + std::size_t(std::count(data, data + i, '\n'));
        char hex[8];
        const char* digits = "0123456789ABCDEF";
        hex[0] = '0', hex[1] = 'x', hex[2] = digits[c >> 4], hex[3] = digits[c & 15], hex[4] = 0;
        return R::failure(name + ":" + std::to_string(line) + ": not a text file (binary byte " + hex +
                          " at offset " + std::to_string(i) + ")");
    }
    const char* text = reinterpret_cast<const char*>(data);
    return R(TextSpan{text + offset, text + size});
}

Result<ObjScanStats> scanObj(TextSpan text, const std::string& name, const LoadLimits& limits) {
    using R = Result<ObjScanStats>;
    ObjScanStats s;
    std::size_t faceVertices = 0, otherIndices = 0, weightTokens = 0, groups = 0, warnBytes = 0;
    std::size_t polygonWork = 0;
    LineCursor lines(text);
    const char* b = nullptr;
    const char* e = nullptr;
    while (lines.next(b, e)) {
        const auto at = [&] { return name + ":" + std::to_string(lines.line()) + ": "; };
        const char* p = skipBlanks(b, e);
        const Kind kind = kindOf(p, e);
        // Coordinates: the ones tinyobjloader reads must be plain numbers (it would turn
        // "nan" into 0 silently). Extra values (w, vertex colours) are not read for geometry.
        if (kind == Kind::Position || kind == Kind::Normal || kind == Kind::TexCoord) {
            std::size_t& count = kind == Kind::Position ? s.positions : kind == Kind::Normal ? s.normals : s.texcoords;
            const char* what = kind == Kind::Position ? "vertex" : kind == Kind::Normal ? "normal" : "texture coordinate";
            if (++count > limits.maxVertices) {
                return R::failure(at() + "more than " + std::to_string(limits.maxVertices) + " " + what +
                                  " entries (the limit)");
            }
            p += kind == Kind::Position ? 2 : 3;
            const int used = kind == Kind::TexCoord ? 2 : 3;
            for (int k = 0; k < used; ++k) {
                p = skipBlanks(p, e);
                if (p >= e) break; // missing values default to 0, as in tinyobjloader
                const char* t = p;
                while (p < e && !isBlank(*p)) ++p;
                if (!isAcceptedNumber(t, p)) {
                    return R::failure(at() + what + " " + std::to_string(count) + ": coordinate " + quoted(t, p) +
                                      " is not a number");
                }
            }
        } else if (kind == Kind::Face) {
            IndexCheck ic{name, lines.line(), {}};
            std::size_t n = 0;
            p = skipBlanks(p + 2, e);
            while (p < e) {
                const char* q = checkTriple(p, e, s, ic);
                if (!q) return R::failure(ic.error);
                if (q == p) return R::failure(at() + "cannot parse face vertex " + quoted(p, e)); // never loops
                p = skipBlanks(q, e);
                if (++n > limits.maxFaceVertices) {
                    return R::failure(at() + "face has more than " + std::to_string(limits.maxFaceVertices) +
                                      " vertices (the limit)");
                }
            }
            faceVertices += n;
            if (n < 3) {
                warnBytes += 32; // tinyobjloader skips it with a warning
                continue;
            }
            ++s.faces;
            s.triangles += n - 2;
            if (n > 4) polygonWork += n * n;
            if (s.triangles > limits.maxTriangles) {
                return R::failure(at() + "more than " + std::to_string(limits.maxTriangles) + " triangles (the limit)");
            }
            if (polygonWork > limits.maxPolygonWork) {
                return R::failure(at() + "too many large polygons to triangulate (sum of squared polygon sizes above " +
                                  std::to_string(limits.maxPolygonWork) + ")");
            }
        } else if (kind == Kind::LineOrPoint) {
            otherIndices += countTokens(p + 2, e);
        } else if (kind == Kind::Weight) {
            weightTokens += countTokens(p + 3, e);
            // "vw vertex joint weight ...": tinyobjloader converts the vertex and joint ids to int
            // with no range check (undefined behaviour for 1e38, found by fuzzing), so every value
            // must be a plain number within int's range. It also computes a number as
            // mantissa * pow(5, exponent) * 2^exponent: "0e999" is 0 * inf = NaN there (0 for
            // strtod), so exponents above 300 (pow(5, 300) is finite) are refused too.
            for (const char* q = skipBlanks(p + 3, e); q < e; q = skipBlanks(q, e)) {
                const char* t = q;
                while (q < e && !isBlank(*q)) ++q;
                const std::string token(t, q);
                long exponent = 0;
                if (!isAcceptedNumber(t, q, &exponent) || exponent > 300 ||
                    !(std::fabs(std::strtod(token.c_str(), nullptr)) <= 2147483647.0))
                    return R::failure(at() + "vertex weight value " + quoted(t, q) + " is not a number in int's range");
            }
        } else if (kind == Kind::Group) {
            ++groups;
        } else if (kind == Kind::UseMtl) {
            ++groups;
            warnBytes += std::size_t(e - p) + 64; // "material not found"/"failed to load" warning, worst case
        }
    }
    // Estimated peak, an upper bound: the text, tinyobjloader's arrays (v + colours, vn, vt, faces
    // before triangulation, triangulated indices and per-face ids, lines/points, weights, shapes,
    // warnings), then our vertex/index arrays, the de-duplication map and the normal accumulators.
    // Measured for a 2M-triangle grid with vt and vn: estimate 0.97 GB, peak RSS 0.41 GB.
    const double est = double(s.positions) * (24 + 24 + 24) + double(s.normals) * 12 + double(s.texcoords) * 8 +
                       double(s.faces) * 128 + double(faceVertices) * 12 + double(s.triangles) * (36 + 12 + 12) +
                       double(s.triangles) * 3 * (32 + 48) + double(otherIndices) * 12 + double(weightTokens) * 8 +
                       double(groups) * 1024 + double(warnBytes) + double(text.end - text.begin);
    s.estimatedBytes = est > 1e18 ? std::size_t(-1) : std::size_t(est);
    if (s.estimatedBytes > limits.maxMemoryBytes) {
        return R::failure(name + ": loading would need about " + std::to_string(s.estimatedBytes >> 20) +
                          " MiB, above the limit of " + std::to_string(limits.maxMemoryBytes >> 20) + " MiB");
    }
    return R(s);
}

std::size_t lineOfEntry(TextSpan text, ObjEntry kind, std::size_t n) {
    const Kind want = kind == ObjEntry::Position ? Kind::Position : kind == ObjEntry::Normal ? Kind::Normal : Kind::TexCoord;
    LineCursor lines(text);
    const char* b = nullptr;
    const char* e = nullptr;
    std::size_t seen = 0;
    while (lines.next(b, e)) {
        if (kindOf(skipBlanks(b, e), e) == want && seen++ == n) return lines.line();
    }
    return 0;
}

std::size_t countMtlMaterials(TextSpan text) {
    LineCursor lines(text);
    const char* b = nullptr;
    const char* e = nullptr;
    std::size_t n = 0;
    while (lines.next(b, e)) {
        const char* p = skipBlanks(b, e);
        if (e - p >= 6 && std::memcmp(p, "newmtl", 6) == 0) ++n;
    }
    return n;
}

} // namespace sr
