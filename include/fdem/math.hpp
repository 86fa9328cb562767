// Small fixed-size 2-D vector and 2x2 matrix types used by every kernel.
// Plain aggregates with inline free operators, so hot loops compile to straight-line code.
#pragma once

#include <cmath>
#include <cstdint>

namespace fdem {

using Real = double;  ///< scalar type of all physics (penalties and small dt make float risky)

using NodeId = int32_t;
using TriId = int32_t;
using BodyId = int32_t;
inline constexpr int32_t kNone = -1;  ///< "no entity" for any id

/// 2-D vector (a point, a displacement, a force per unit thickness, ...).
struct Vec2 {
    Real x = 0, y = 0;
};

inline Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
inline Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
inline Vec2 operator-(Vec2 a) { return {-a.x, -a.y}; }
inline Vec2 operator*(Real s, Vec2 a) { return {s * a.x, s * a.y}; }
inline Vec2 operator*(Vec2 a, Real s) { return {s * a.x, s * a.y}; }
inline Vec2 operator/(Vec2 a, Real s) { return {a.x / s, a.y / s}; }
inline Vec2& operator+=(Vec2& a, Vec2 b) { a.x += b.x; a.y += b.y; return a; }
inline Vec2& operator-=(Vec2& a, Vec2 b) { a.x -= b.x; a.y -= b.y; return a; }
inline Vec2& operator*=(Vec2& a, Real s) { a.x *= s; a.y *= s; return a; }
inline bool operator==(Vec2 a, Vec2 b) { return a.x == b.x && a.y == b.y; }
inline Real dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
/// z-component of the 3-D cross product (a, 0) x (b, 0).
inline Real cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }
inline Real norm(Vec2 a) { return std::sqrt(dot(a, a)); }
inline Real norm2(Vec2 a) { return dot(a, a); }
/// a rotated by +90 degrees: e_z x a.
inline Vec2 perp(Vec2 a) { return {-a.y, a.x}; }

/// 2x2 matrix, row-major: [[xx, xy], [yx, yy]].
struct Mat2 {
    Real xx = 0, xy = 0, yx = 0, yy = 0;
};

inline Mat2 identity2() { return {1, 0, 0, 1}; }
/// matrix whose columns are a and b.
inline Mat2 columns(Vec2 a, Vec2 b) { return {a.x, b.x, a.y, b.y}; }
inline Mat2 operator+(const Mat2& a, const Mat2& b) {
    return {a.xx + b.xx, a.xy + b.xy, a.yx + b.yx, a.yy + b.yy};
}
inline Mat2 operator-(const Mat2& a, const Mat2& b) {
    return {a.xx - b.xx, a.xy - b.xy, a.yx - b.yx, a.yy - b.yy};
}
inline Mat2 operator*(Real s, const Mat2& a) { return {s * a.xx, s * a.xy, s * a.yx, s * a.yy}; }
inline Mat2 operator*(const Mat2& a, const Mat2& b) {
    return {a.xx * b.xx + a.xy * b.yx, a.xx * b.xy + a.xy * b.yy,
            a.yx * b.xx + a.yy * b.yx, a.yx * b.xy + a.yy * b.yy};
}
inline Vec2 operator*(const Mat2& a, Vec2 v) {
    return {a.xx * v.x + a.xy * v.y, a.yx * v.x + a.yy * v.y};
}
inline Mat2 transpose(const Mat2& a) { return {a.xx, a.yx, a.xy, a.yy}; }
inline Real det(const Mat2& a) { return a.xx * a.yy - a.xy * a.yx; }
inline Real trace(const Mat2& a) { return a.xx + a.yy; }
inline Mat2 inverse(const Mat2& a) {
    const Real inv = 1.0 / det(a);
    return {a.yy * inv, -a.xy * inv, -a.yx * inv, a.xx * inv};
}
/// Frobenius inner product a : b.
inline Real ddot(const Mat2& a, const Mat2& b) {
    return a.xx * b.xx + a.xy * b.xy + a.yx * b.yx + a.yy * b.yy;
}

/// Signed area of triangle (a, b, c); positive when counter-clockwise.
inline Real signed_area(Vec2 a, Vec2 b, Vec2 c) { return 0.5 * cross(b - a, c - a); }

}  // namespace fdem
