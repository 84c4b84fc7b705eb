#include "writers/py_json.h"

#include <charconv>
#include <cmath>
#include <cstdio>

namespace sdg {
namespace {

void appendString(std::string& out, const std::string& s) {
  out += '"';
  // Decode UTF-8 so non-ASCII characters become \uXXXX (surrogate pairs above U+FFFF).
  for (size_t i = 0; i < s.size();) {
    unsigned char c = static_cast<unsigned char>(s[i]);
    uint32_t cp = c;
    size_t len = 1;
    if (c >= 0xF0) { cp = c & 0x07; len = 4; }
    else if (c >= 0xE0) { cp = c & 0x0F; len = 3; }
    else if (c >= 0xC0) { cp = c & 0x1F; len = 2; }
    if (len > 1) {
      if (i + len > s.size()) { cp = 0xFFFD; len = s.size() - i; }
      else for (size_t k = 1; k < len; ++k) cp = (cp << 6) | (static_cast<unsigned char>(s[i + k]) & 0x3F);
    }
    i += len;
    char buf[16];
    switch (cp) {
      case '"': out += "\\\""; continue;
      case '\\': out += "\\\\"; continue;
      case '\n': out += "\\n"; continue;
      case '\r': out += "\\r"; continue;
      case '\t': out += "\\t"; continue;
      case '\b': out += "\\b"; continue;
      case '\f': out += "\\f"; continue;
      default: break;
    }
    if (cp < 0x20 || (cp >= 0x7F && cp < 0x10000)) {
      std::snprintf(buf, sizeof buf, "\\u%04x", cp);
      out += buf;
    } else if (cp >= 0x10000) {
      cp -= 0x10000;
      std::snprintf(buf, sizeof buf, "\\u%04x\\u%04x", 0xD800 + (cp >> 10), 0xDC00 + (cp & 0x3FF));
      out += buf;
    } else {
      out += char(cp);
    }
  }
  out += '"';
}

void appendFloat(std::string& out, double v) {
  if (std::isnan(v)) { out += "NaN"; return; }
  if (std::isinf(v)) { out += v > 0 ? "Infinity" : "-Infinity"; return; }
  // Python's repr: the shortest round-trip digits; exponent form when the
  // decimal exponent is < -4 or >= 16, written as 1e-05 / 1e+16.
  char buf[64];
  auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::scientific);
  std::string sci(buf, end);  // d.ddde[+-]XX
  size_t e = sci.find('e');
  std::string digits = sci.substr(0, e);
  int exponent = std::stoi(sci.substr(e + 1));
  std::string mantissa;
  for (char c : digits) if (c != '.' && c != '-') mantissa += c;
  bool negative = v < 0;
  std::string text;
  if (exponent < -4 || exponent >= 16) {
    text = mantissa.substr(0, 1);
    if (mantissa.size() > 1) text += "." + mantissa.substr(1);
    std::snprintf(buf, sizeof buf, "e%c%02d", exponent < 0 ? '-' : '+', std::abs(exponent));
    text += buf;
  } else if (exponent >= 0) {
    if (int(mantissa.size()) <= exponent + 1) text = mantissa + std::string(size_t(exponent + 1) - mantissa.size(), '0') + ".0";
    else text = mantissa.substr(0, size_t(exponent + 1)) + "." + mantissa.substr(size_t(exponent + 1));
  } else {
    text = "0." + std::string(size_t(-exponent - 1), '0') + mantissa;
  }
  out += (negative ? "-" : "") + text;
}

void dump(std::string& out, const nlohmann::ordered_json& j) {
  switch (j.type()) {
    case nlohmann::json::value_t::object: {
      out += '{';
      bool first = true;
      for (const auto& [k, v] : j.items()) {
        if (!first) out += ", ";
        first = false;
        appendString(out, k);
        out += ": ";
        dump(out, v);
      }
      out += '}';
      break;
    }
    case nlohmann::json::value_t::array: {
      out += '[';
      for (size_t i = 0; i < j.size(); ++i) {
        if (i) out += ", ";
        dump(out, j[i]);
      }
      out += ']';
      break;
    }
    case nlohmann::json::value_t::string: appendString(out, j.get_ref<const std::string&>()); break;
    case nlohmann::json::value_t::boolean: out += j.get<bool>() ? "true" : "false"; break;
    case nlohmann::json::value_t::number_integer: out += std::to_string(j.get<int64_t>()); break;
    case nlohmann::json::value_t::number_unsigned: out += std::to_string(j.get<uint64_t>()); break;
    case nlohmann::json::value_t::number_float: appendFloat(out, j.get<double>()); break;
    default: out += "null"; break;
  }
}

}  // namespace

std::string pythonJsonDumps(const nlohmann::ordered_json& value) {
  std::string out;
  dump(out, value);
  return out;
}

}  // namespace sdg
