/* scene_gltf_util.cpp - what every step of the glTF load uses (scene_gltf_internal.h): message
 * formatting and the LoadFail throwers, uri and path helpers, accessor type sizes, range-checked
 * bufferView bytes and attribute lookup. A leaf: it calls no step of the loader.
 */
#include "scene_gltf_internal.h"

#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <string>
#include <utility>

namespace pg_gltf {

std::string strf(const char *fmt, ...)
{
    char buf[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    return buf;
}

[[noreturn]] void fail(pg_result code, std::string msg) { throw LoadFail{code, std::move(msg)}; }
[[noreturn]] void gfail(std::string msg) { fail(PG_ERR_GLTF, std::move(msg)); }

/* A short, printable form of a uri for messages (data URIs are not quoted whole). */
std::string uri_desc(const std::string &uri)
{
    if (uri.compare(0, 5, "data:") == 0) return "data URI";
    std::string s = uri.size() > 200 ? uri.substr(0, 200) + "..." : uri;
    return "'" + s + "'";
}

/* tinygltf decodes external uris with dlib::urldecode ('+' -> ' ', %XX); do the same. */
std::string url_decode(const std::string &s)
{
    auto hex = [](unsigned char c) -> unsigned {
        if (c >= '0' && c <= '9') return c - '0';
        if (c >= 'a' && c <= 'f') return c - 'a' + 10;
        if (c >= 'A' && c <= 'F') return c - 'A' + 10;
        return 0;
    };
    std::string r;
    for (size_t i = 0; i < s.size(); i++) {
        if (s[i] == '+') {
            r += ' ';
        } else if (s[i] == '%' && s.size() > i + 2) {
            r += char((hex((unsigned char)s[i + 1]) << 4) | hex((unsigned char)s[i + 2]));
            i += 2;
        } else {
            r += s[i];
        }
    }
    return r;
}

std::string join_path(const std::string &dir, const std::string &file)
{
    if (dir.empty()) return file;
    if (dir.back() == '/') return dir + file;
    return dir + "/" + file;
}

int type_comps(int t)
{
    switch (t) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    case TINYGLTF_TYPE_MAT2: return 4;
    case TINYGLTF_TYPE_MAT3: return 9;
    case TINYGLTF_TYPE_MAT4: return 16;
    default: return 0;
    }
}

const char *ctype_name(int ct)
{
    switch (ct) {
    case 5120: return "BYTE";
    case 5121: return "UNSIGNED_BYTE";
    case 5122: return "SHORT";
    case 5123: return "UNSIGNED_SHORT";
    case 5125: return "UNSIGNED_INT";
    case 5126: return "FLOAT";
    default: return "?";
    }
}

size_t ctype_size(int ct)
{
    switch (ct) {
    case 5120:
    case 5121: return 1;
    case 5122:
    case 5123: return 2;
    case 5125:
    case 5126: return 4;
    default: return 0;
    }
}

/* The bytes of bufferViews[bvi] (range-checked against its buffer). */
std::pair<const unsigned char *, size_t> view_bytes(const Ctx &c, int bvi, const std::string &who)
{
    const tinygltf::Model &m = c.model;
    if (bvi < 0 || size_t(bvi) >= m.bufferViews.size())
        gfail(strf("%s: bufferView %d out of range", who.c_str(), bvi));
    const tinygltf::BufferView &bv = m.bufferViews[size_t(bvi)];
    auto dec = c.decoded.find(bvi);
    if (dec != c.decoded.end()) return {dec->second.data(), dec->second.size()};
    if (bv.buffer < 0 || size_t(bv.buffer) >= m.buffers.size())
        gfail(strf("bufferViews[%d]: buffer %d out of range", bvi, bv.buffer));
    const tinygltf::Buffer &buf = m.buffers[size_t(bv.buffer)];
    uint64_t blen = buf.data.size();
    if (bv.byteOffset > blen || bv.byteLength > blen - bv.byteOffset)
        gfail(strf("bufferViews[%d]: byteOffset %zu + byteLength %zu exceeds buffers[%d] "
                   "(%llu bytes)",
                   bvi, bv.byteOffset, bv.byteLength, bv.buffer, (unsigned long long)blen));
    return {buf.data.data() + bv.byteOffset, bv.byteLength};
}

const int *find_attr(const tinygltf::Primitive &p, const char *name)
{
    auto it = p.attributes.find(name);
    return it == p.attributes.end() ? nullptr : &it->second;
}

/* ---- matrices (column-major 4x4, double) ---- */

Mat4 mat_identity()
{
    Mat4 r{};
    r.m[0] = r.m[5] = r.m[10] = r.m[15] = 1.0;
    return r;
}

Mat4 mat_mul(const Mat4 &a, const Mat4 &b)
{
    Mat4 r{};
    for (int col = 0; col < 4; col++)
        for (int row = 0; row < 4; row++) {
            double s = 0;
            for (int k = 0; k < 4; k++) s += a.m[k * 4 + row] * b.m[col * 4 + k];
            r.m[col * 4 + row] = s;
        }
    return r;
}

Mat4 mat_trs(const double t[3], const double q_in[4], const double s[3], const std::string &rot_where)
{
    Mat4 r = mat_identity();
    double q[4] = {q_in[0], q_in[1], q_in[2], q_in[3]};
    double l = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    if (!(l > 1e-12)) gfail(rot_where + ": zero-length quaternion");
    for (double &x : q) x /= l;
    double x = q[0], y = q[1], z = q[2], w = q[3];
    double R[9] = {1 - 2 * (y * y + z * z), 2 * (x * y + z * w),     2 * (x * z - y * w),
                   2 * (x * y - z * w),     1 - 2 * (x * x + z * z), 2 * (y * z + x * w),
                   2 * (x * z + y * w),     2 * (y * z - x * w),     1 - 2 * (x * x + y * y)};
    /* R is column-major: column c = R[c*3 .. c*3+2]; M = T * R * S */
    for (int col = 0; col < 3; col++)
        for (int row = 0; row < 3; row++) r.m[col * 4 + row] = R[col * 3 + row] * s[col];
    r.m[12] = t[0];
    r.m[13] = t[1];
    r.m[14] = t[2];
    return r;
}

} // namespace pg_gltf
