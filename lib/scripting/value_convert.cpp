#include "scripting/value_convert.h"

#include <cstdlib>

#include "core/text.h"

namespace py = pybind11;

namespace sdg::scripting {
namespace {

double floatToPython(float f) { return std::strtod(text::formatFloat(f).c_str(), nullptr); }

std::string typeNameOf(py::handle object) { return py::str(py::type::handle_of(object).attr("__name__")); }

[[noreturn]] void mismatch(const std::string& what, std::string_view expected, py::handle found) {
  throw py::type_error(what + ": expected " + std::string(expected) + ", found " + typeNameOf(found) + " " +
                       std::string(py::repr(found)));
}

bool isBoolLike(py::handle o) {
  if (py::isinstance<py::bool_>(o)) return true;
  const std::string name = typeNameOf(o);
  return name == "bool_";  // numpy.bool_
}

double number(py::handle o, const std::string& what) {
  if (isBoolLike(o) || py::isinstance<py::str>(o) || !PyNumber_Check(o.ptr())) mismatch(what, "a number", o);
  double d = PyFloat_AsDouble(o.ptr());
  if (d == -1.0 && PyErr_Occurred()) throw py::error_already_set();
  return d;
}

int64_t integer(py::handle o, const std::string& what, int64_t low, int64_t high) {
  if (isBoolLike(o) || !PyIndex_Check(o.ptr())) mismatch(what, "an integer", o);
  py::object index = py::reinterpret_steal<py::object>(PyNumber_Index(o.ptr()));
  if (!index) throw py::error_already_set();
  int overflow = 0;
  long long v = PyLong_AsLongLongAndOverflow(index.ptr(), &overflow);
  if (overflow != 0 || v < low || v > high)
    throw py::value_error(what + ": " + std::string(py::repr(o)) + " is outside " + std::to_string(low) + " .. " +
                          std::to_string(high));
  return v;
}

std::vector<py::object> items(py::handle o, size_t count, const std::string& what, std::string_view shape) {
  if (py::isinstance<py::str>(o) || py::isinstance<py::bytes>(o) || !PySequence_Check(o.ptr())) mismatch(what, shape, o);
  py::sequence seq = py::reinterpret_borrow<py::sequence>(o);
  if (count != 0 && seq.size() != count)
    throw py::value_error(what + ": expected " + std::string(shape) + ", found " + std::to_string(seq.size()) +
                          " items");
  std::vector<py::object> out;
  out.reserve(seq.size());
  for (size_t i = 0; i < seq.size(); ++i) out.push_back(seq[i]);
  return out;
}

std::string string(py::handle o, const std::string& what) {
  if (!py::isinstance<py::str>(o)) mismatch(what, "a string", o);
  return o.cast<std::string>();
}

template <typename V, int N>
V numbers(py::handle o, const std::string& what, std::string_view shape) {
  std::vector<py::object> xs = items(o, N, what, shape);
  V v;
  for (int i = 0; i < N; ++i) v[i] = static_cast<typename V::Scalar>(number(xs[size_t(i)], what));
  return v;
}

}  // namespace

py::tuple vec3ToPython(const Vec3d& v) { return py::make_tuple(v.x(), v.y(), v.z()); }

py::tuple matrix3ToPython(const Matrix3d& m) {
  return py::make_tuple(py::make_tuple(m(0, 0), m(0, 1), m(0, 2)), py::make_tuple(m(1, 0), m(1, 1), m(1, 2)),
                        py::make_tuple(m(2, 0), m(2, 1), m(2, 2)));
}

Vec3d vec3FromPython(py::handle object, const std::string& what) {
  return numbers<Vec3d, 3>(object, what, "a sequence of 3 numbers");
}

Matrix3d matrix3FromPython(py::handle object, const std::string& what) {
  std::vector<py::object> rows = items(object, 3, what, "a 3x3 matrix (3 rows of 3 numbers)");
  Matrix3d m;
  for (int r = 0; r < 3; ++r) m.row(r) = numbers<Vec3d, 3>(rows[size_t(r)], what, "a row of 3 numbers").transpose();
  return m;
}

py::object toPython(const Value& v) {
  switch (v.type()) {
    case ValueType::Bool: return py::bool_(v.get<bool>());
    case ValueType::Int: return py::int_(v.get<int32_t>());
    case ValueType::UInt: return py::int_(v.get<uint32_t>());
    case ValueType::Float: return py::float_(floatToPython(v.get<float>()));
    case ValueType::Double: return py::float_(v.get<double>());
    case ValueType::Int2: return py::make_tuple(v.get<Vec2i>().x(), v.get<Vec2i>().y());
    case ValueType::Float2:
      return py::make_tuple(floatToPython(v.get<Vec2f>().x()), floatToPython(v.get<Vec2f>().y()));
    case ValueType::Float3:
    case ValueType::Color3f: {
      const Vec3f& x = v.get<Vec3f>();
      return py::make_tuple(floatToPython(x.x()), floatToPython(x.y()), floatToPython(x.z()));
    }
    case ValueType::Double3:
    case ValueType::Vector3d: return vec3ToPython(v.get<Vec3d>());
    case ValueType::Quatf: {
      const Quatf& q = v.get<Quatf>();
      return py::make_tuple(floatToPython(q.w()), floatToPython(q.x()), floatToPython(q.y()), floatToPython(q.z()));
    }
    case ValueType::Quatd: {
      const Quatd& q = v.get<Quatd>();
      return py::make_tuple(q.w(), q.x(), q.y(), q.z());
    }
    case ValueType::Matrix4d: {
      const Matrix4d& m = v.get<Matrix4d>();
      py::list rows;
      for (int c = 0; c < 4; ++c) rows.append(py::make_tuple(m(0, c), m(1, c), m(2, c), m(3, c)));
      return py::tuple(rows);
    }
    case ValueType::String:
    case ValueType::Token:
    case ValueType::Asset: return py::str(v.get<std::string>());
    case ValueType::AssetArray:
    case ValueType::StringArray: {
      py::list list;
      for (const std::string& s : v.get<std::vector<std::string>>()) list.append(py::str(s));
      return list;
    }
    case ValueType::IntArray: {
      py::list list;
      for (int32_t i : v.get<IntArray>().items()) list.append(py::int_(i));
      return list;
    }
    case ValueType::FloatArray:
    case ValueType::Point3fArray:
    case ValueType::Normal3fArray:
    case ValueType::Color3fArray:
    case ValueType::TexCoord2fArray: {
      // float[] flat; the tuple types one tuple per item.
      const size_t width = size_t(arrayWidth(v.type()));
      const FloatArray& a = v.get<FloatArray>();
      py::list list;
      for (size_t i = 0; i < a.size(); i += width) {
        if (width == 1) {
          list.append(py::float_(floatToPython(a[i])));
          continue;
        }
        py::list item;
        for (size_t k = 0; k < width; ++k) item.append(py::float_(floatToPython(a[i + k])));
        list.append(py::tuple(item));
      }
      return list;
    }
  }
  return py::none();
}

Value fromPython(py::handle o, ValueType type, const std::string& what) {
  switch (type) {
    case ValueType::Bool:
      if (!isBoolLike(o)) mismatch(what, "True or False", o);
      return Value::makeBool(o.cast<bool>());
    case ValueType::Int: return Value::makeInt(int32_t(integer(o, what, INT32_MIN, INT32_MAX)));
    case ValueType::UInt: return Value::makeUInt(uint32_t(integer(o, what, 0, UINT32_MAX)));
    case ValueType::Float: return Value::makeFloat(static_cast<float>(number(o, what)));
    case ValueType::Double: return Value::makeDouble(number(o, what));
    case ValueType::Int2: {
      std::vector<py::object> xs = items(o, 2, what, "a sequence of 2 integers");
      return Value::makeInt2(int32_t(integer(xs[0], what, INT32_MIN, INT32_MAX)),
                             int32_t(integer(xs[1], what, INT32_MIN, INT32_MAX)));
    }
    case ValueType::Float2: {
      Vec2f f = numbers<Vec2f, 2>(o, what, "a sequence of 2 numbers");
      return Value::makeFloat2(f.x(), f.y());
    }
    case ValueType::Float3: return Value::makeFloat3(numbers<Vec3f, 3>(o, what, "a sequence of 3 numbers"));
    case ValueType::Color3f: return Value::makeColor3f(numbers<Vec3f, 3>(o, what, "a sequence of 3 numbers (r, g, b)"));
    case ValueType::Double3: return Value::makeDouble3(vec3FromPython(o, what));
    case ValueType::Vector3d: return Value::makeVector3d(vec3FromPython(o, what));
    case ValueType::Quatf: {
      Eigen::Vector4f q = numbers<Eigen::Vector4f, 4>(o, what, "a sequence of 4 numbers (w, x, y, z)");
      return Value::makeQuatf(Quatf(q[0], q[1], q[2], q[3]));
    }
    case ValueType::Quatd: {
      Eigen::Vector4d q = numbers<Eigen::Vector4d, 4>(o, what, "a sequence of 4 numbers (w, x, y, z)");
      return Value::makeQuatd(Quatd(q[0], q[1], q[2], q[3]));
    }
    case ValueType::Matrix4d: {
      std::vector<py::object> rows = items(o, 4, what, "a 4x4 matrix (4 rows of 4 numbers)");
      Matrix4d m;
      for (int r = 0; r < 4; ++r)
        m.col(r) = numbers<Eigen::Vector4d, 4>(rows[size_t(r)], what, "a row of 4 numbers");  // USD rows
      return Value::makeMatrix4d(m);
    }
    case ValueType::String: return Value::makeString(string(o, what));
    case ValueType::Token: return Value::makeToken(string(o, what));
    case ValueType::Asset: return Value::makeAsset(string(o, what));
    case ValueType::AssetArray:
    case ValueType::StringArray: {
      std::vector<std::string> list;
      for (const py::object& item : items(o, 0, what, "a list of strings")) list.push_back(string(item, what));
      return type == ValueType::AssetArray ? Value::makeAssetArray(std::move(list))
                                           : Value::makeStringArray(std::move(list));
    }
    case ValueType::IntArray: {
      std::vector<int32_t> list;
      for (const py::object& item : items(o, 0, what, "a list of integers"))
        list.push_back(int32_t(integer(item, what, INT32_MIN, INT32_MAX)));
      return Value::makeIntArray(std::move(list));
    }
    case ValueType::FloatArray:
    case ValueType::Point3fArray:
    case ValueType::Normal3fArray:
    case ValueType::Color3fArray:
    case ValueType::TexCoord2fArray: {
      const size_t width = size_t(arrayWidth(type));
      std::vector<float> flat;
      for (const py::object& item : items(o, 0, what, valueTypeShape(type))) {
        if (width == 1) {
          flat.push_back(static_cast<float>(number(item, what)));
          continue;
        }
        for (const py::object& c : items(item, width, what, "an item of " + std::to_string(width) + " numbers"))
          flat.push_back(static_cast<float>(number(c, what)));
      }
      return Value::makeFloatArray(type, std::move(flat));
    }
  }
  throw py::type_error(what + ": unsupported type");
}

}  // namespace sdg::scripting
