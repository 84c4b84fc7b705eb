#include "stage/value_json.h"

#include <cstdlib>

#include "core/text.h"

namespace sdg {
namespace {

using Json = nlohmann::ordered_json;

// Floats go through their shortest text so 20.955f stays 20.955 in JSON.
double floatJson(float f) { return std::strtod(text::formatFloat(f).c_str(), nullptr); }

}  // namespace

Json valueToJson(const Value& v) {
  switch (v.type()) {
    case ValueType::Bool: return v.get<bool>();
    case ValueType::Int: return v.get<int32_t>();
    case ValueType::UInt: return v.get<uint32_t>();
    case ValueType::Float: return floatJson(v.get<float>());
    case ValueType::Double: return v.get<double>();
    case ValueType::Int2: return Json::array({v.get<Vec2i>().x(), v.get<Vec2i>().y()});
    case ValueType::Float2: return Json::array({floatJson(v.get<Vec2f>().x()), floatJson(v.get<Vec2f>().y())});
    case ValueType::Float3:
    case ValueType::Color3f: {
      const Vec3f& x = v.get<Vec3f>();
      return Json::array({floatJson(x.x()), floatJson(x.y()), floatJson(x.z())});
    }
    case ValueType::Double3:
    case ValueType::Vector3d: {
      const Vec3d& x = v.get<Vec3d>();
      return Json::array({x.x(), x.y(), x.z()});
    }
    case ValueType::Quatf: {
      const Quatf& q = v.get<Quatf>();
      return Json::array({floatJson(q.w()), floatJson(q.x()), floatJson(q.y()), floatJson(q.z())});
    }
    case ValueType::Quatd: {
      const Quatd& q = v.get<Quatd>();
      return Json::array({q.w(), q.x(), q.y(), q.z()});
    }
    case ValueType::Matrix4d: {
      Json rows = Json::array();
      const Matrix4d& m = v.get<Matrix4d>();
      for (int c = 0; c < 4; ++c) rows.push_back(Json::array({m(0, c), m(1, c), m(2, c), m(3, c)}));
      return rows;
    }
    case ValueType::String:
    case ValueType::Token:
    case ValueType::Asset: return v.get<std::string>();
    case ValueType::AssetArray:
    case ValueType::StringArray: return v.get<std::vector<std::string>>();
    case ValueType::IntArray: {
      std::span<const int32_t> items = v.get<IntArray>().items();
      return Json(std::vector<int32_t>(items.begin(), items.end()));
    }
    case ValueType::FloatArray:
    case ValueType::Point3fArray:
    case ValueType::Normal3fArray:
    case ValueType::Color3fArray:
    case ValueType::TexCoord2fArray: {
      // Flat for float[], one list per item for the tuple types.
      const size_t width = size_t(arrayWidth(v.type()));
      const FloatArray& a = v.get<FloatArray>();
      Json out = Json::array();
      for (size_t i = 0; i < a.size(); i += width) {
        if (width == 1) {
          out.push_back(floatJson(a[i]));
          continue;
        }
        Json item = Json::array();
        for (size_t k = 0; k < width; ++k) item.push_back(floatJson(a[i + k]));
        out.push_back(std::move(item));
      }
      return out;
    }
  }
  return nullptr;
}


}  // namespace sdg
