#pragma once
// Linear-algebra types shared by the whole project. Matrices use the
// column-vector convention (p_world = M * p_local, translation in column 3);
// conversion to USD's row-vector layout happens only at the file boundaries.
#include <Eigen/Geometry>

namespace sdg {

using Vec2i = Eigen::Vector2i;
using Vec2f = Eigen::Vector2f;
using Vec3f = Eigen::Vector3f;
using Vec3d = Eigen::Vector3d;
using Quatf = Eigen::Quaternionf;
using Quatd = Eigen::Quaterniond;
using Matrix4d = Eigen::Matrix4d;
using Matrix3d = Eigen::Matrix3d;

}  // namespace sdg
