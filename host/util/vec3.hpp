// vec3.hpp - a minimal 3-vector: double (Vec3) for the scene and the
// reference renderer, float for the OpenMP comparison tracer (bench/).
#pragma once
#include <cmath>

namespace clrt {

template <class T>
struct Vector3 {
  T x = 0, y = 0, z = 0;
};
using Vec3 = Vector3<double>;

// The scalar's type comes from the vector (2 * v is a Vector3<T> product).
template <class T>
struct ScalarOf {
  using type = T;
};

template <class T>
inline Vector3<T> operator+(Vector3<T> a, Vector3<T> b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
template <class T>
inline Vector3<T> operator-(Vector3<T> a, Vector3<T> b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
template <class T>
inline Vector3<T> operator*(typename ScalarOf<T>::type k, Vector3<T> a) {
  return {k * a.x, k * a.y, k * a.z};
}
template <class T>
inline T dot(Vector3<T> a, Vector3<T> b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <class T>
inline Vector3<T> cross(Vector3<T> a, Vector3<T> b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <class T>
inline T length(Vector3<T> a) {
  return std::sqrt(dot(a, a));
}

}  // namespace clrt
