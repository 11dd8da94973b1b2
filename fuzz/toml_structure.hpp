// Builds a TOML document's STRUCTURE from fuzzer bytes (fuzz/fuzz_toml_structure.cpp): a
// byte-level mutator rarely turns a scene into a 2000-deep table or a 100000-element array,
// which is where a recursive reader or a quadratic walk fails. The first byte picks a base
// scene (or none); every further group of bytes appends one construct, whose sizes come
// from the bytes that follow:
//   deep table headers        [bodies.a.b.c. ... ]          (depth up to 4096)
//   long dotted keys          bodies.x.y. ... .z = VALUE     (up to 4096 parts)
//   deep arrays               k = [[[[ ... VALUE ... ]]]]    (depth up to 4096)
//   deep inline tables        k = { a = { b = { ... } } }    (depth up to 4096)
//   huge arrays               k = [V, V, V, ...]             (up to 200000 elements)
//   many tables               [bodies.bN] type = ... x N     (up to 5000)
//   arrays of tables          [[impedances.x.points]] x N
//   a value at a scene key    bodies.NAME.KEY = VALUE (numbers at the edges, strings, dates)
// Names and keys come from a vocabulary of the scene format's own, so that the scene
// builder, not only the TOML parser, sees the structures.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace stiction::fuzz {

class ByteReader {
 public:
  ByteReader(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  bool empty() const { return pos_ >= size_; }
  std::uint8_t byte() { return pos_ < size_ ? data_[pos_++] : 0; }
  // A size in [0, limit]: one byte spread on a log scale, so that small and huge are
  // equally likely.
  std::size_t size(std::size_t limit) {
    const std::uint8_t b = byte();
    std::size_t n = b & 0x0f;
    for (int i = 0; i < (b >> 4) && n < limit; ++i) n = n * 2 + 1;
    return n < limit ? n : limit;
  }
  template <std::size_t N>
  std::string_view pick(const std::string_view (&items)[N]) {
    return items[byte() % N];
  }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
};

inline constexpr std::string_view kKeys[] = {
    "bodies",    "impedances", "simulation", "render",    "plots",   "type",     "mass",
    "position",  "velocity",   "orientation", "radius",   "size",    "shape",    "body",
    "other",     "joint",      "joints",     "points",    "normal",  "stiffness", "damping",
    "mu",        "dt",         "duration",   "output_rate", "integrator", "file", "angles",
    "rates",     "name",       "parent",     "axis",      "origin",  "rpy",      "links",
    "force",     "torque",     "expression", "value",     "signal",  "a",        "b",
    "camera",    "inertia",    "initial_e",  "settle",    "tilt",    "belt_speed", "x"};

inline constexpr std::string_view kTypes[] = {
    "\"rigid_body\"", "\"point_mass\"", "\"spatial_tree\"", "\"urdf\"", "\"planar_arm\"",
    "\"kikuuwe_contact\"", "\"kikuuwe_friction\"", "\"spring_damper\"", "\"joint_limit\"",
    "\"force_source\"", "\"lugre_friction\"", "\"dahl_friction\"", "\"cylinder\"", "\"box\"",
    "\"sphere\"", "\"rk4\"", "\"euler\"", "\"rk4_adaptive\""};

inline constexpr std::string_view kValues[] = {
    "0", "-0.0", "1", "-1", "1e308", "-1e308", "5e-324", "nan", "inf", "-inf", "1e-200",
    "9223372036854775807", "-9223372036854775808", "0x7fffffff", "0.1", "1e6", "[0.0, 0.0, 1.0]",
    "[1, 0, 0, 0]", "[1e308, 1e308, 1e308, 1e308]", "[]", "{}", "\"\"", "\"a.b\"", "\"t\"",
    "\"sin(t)\"", "\"1/0\"", "true", "false", "1979-05-27T07:32:00Z", "07:32:00", "'''x'''",
    "\"\\u0000\"", "[[1, 2], [3, 4]]", "{ x = 1 }"};

inline std::string key_path(ByteReader& in, std::size_t parts) {
  std::string path = "bodies";
  for (std::size_t i = 0; i < parts; ++i) {
    path += '.';
    path += in.pick(kKeys);
  }
  return path;
}

inline std::string value(ByteReader& in) {
  return std::string((in.byte() & 1) != 0 ? in.pick(kValues) : in.pick(kTypes));
}

inline void append_construct(ByteReader& in, std::string& out) {
  const std::uint8_t kind = in.byte() % 9;
  // Each construct starts on a fresh line under a fresh table so that earlier ones cannot
  // swallow it; a table defined twice is an ordinary error the parser reports.
  const std::string root = "fz" + std::to_string(out.size());
  switch (kind) {
    case 0: {  // deep table header
      out += "\n[" + key_path(in, in.size(4096)) + "]\n" + std::string(in.pick(kKeys)) + " = " +
             value(in) + "\n";
      break;
    }
    case 1: {  // long dotted key
      out += "\n" + key_path(in, in.size(4096)) + " = " + value(in) + "\n";
      break;
    }
    case 2: {  // deep array
      const std::size_t depth = in.size(4096);
      out += "\n" + root + " = " + std::string(depth, '[') + value(in) + std::string(depth, ']') +
             "\n";
      break;
    }
    case 3: {  // deep inline table
      const std::size_t depth = in.size(4096);
      out += "\n" + root + " = ";
      for (std::size_t i = 0; i < depth; ++i) out += "{ " + std::string(in.pick(kKeys)) + " = ";
      out += value(in);
      for (std::size_t i = 0; i < depth; ++i) out += " }";
      out += "\n";
      break;
    }
    case 4: {  // huge array at a scene key or a fresh one
      const std::size_t count = in.size(200000);
      const std::string element = value(in);
      out += "\n" + ((in.byte() & 1) != 0 ? key_path(in, 2) : root) + " = [";
      for (std::size_t i = 0; i < count; ++i) {
        if (i > 0) out += ", ";
        out += element;
      }
      out += "]\n";
      break;
    }
    case 5: {  // many tables
      const std::size_t count = in.size(5000);
      const std::string type(in.pick(kTypes));
      const std::string section = (in.byte() & 1) != 0 ? "bodies" : "impedances";
      for (std::size_t i = 0; i < count; ++i) {
        out += "\n[" + section + "." + root + "_" + std::to_string(i) + "]\ntype = " + type + "\n";
      }
      break;
    }
    case 6: {  // array of tables
      const std::size_t count = in.size(5000);
      const std::string path = key_path(in, 1 + in.byte() % 3);
      for (std::size_t i = 0; i < count; ++i) {
        out += "\n[[" + path + "]]\n" + std::string(in.pick(kKeys)) + " = " + value(in) + "\n";
      }
      break;
    }
    case 7: {  // long key and long string
      const std::size_t length = in.size(1 << 20);
      out += "\n" + root + std::string(length / 2, 'k') + " = \"" + std::string(length, 's') + "\"\n";
      break;
    }
    default: {  // a value at a scene key
      out += "\n" + key_path(in, 2) + " = " + value(in) + "\n";
      break;
    }
  }
}

// The document: base (chosen by the caller from the first byte) then the constructs.
inline std::string toml_structure(ByteReader& in, const std::string& base) {
  std::string out = base;
  for (int i = 0; i < 16 && !in.empty(); ++i) append_construct(in, out);
  return out;
}

}  // namespace stiction::fuzz
