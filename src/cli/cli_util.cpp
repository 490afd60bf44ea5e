#include "cli/cli_util.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>

#include "conformesh/remesh_schema.h"

namespace conformesh::cli {

bool Args::has(const std::string& name) const {
  for (const auto& f : flags)
    if (f.first == name) return true;
  return false;
}

std::string Args::get(const std::string& name, const std::string& fallback) const {
  for (const auto& f : flags)
    if (f.first == name) return f.second;
  return fallback;
}

double Args::number(const std::string& name, double fallback) const {
  if (!has(name)) return fallback;
  std::string v = get(name);
  char* end = nullptr;
  errno = 0;
  double d = std::strtod(v.c_str(), &end);
  if (v.empty() || end != v.c_str() + v.size() || errno == ERANGE || !std::isfinite(d))
    fail(Code::InvalidArgument, Stage::Api, "option " + name + " needs a number, got '" + v + "'");
  return d;
}

Args parseArgs(const std::vector<std::string>& args, const std::vector<std::string>& valueFlags,
               const std::vector<std::string>& switches) {
  Args out;
  auto contains = [](const std::vector<std::string>& v, const std::string& s) {
    return std::find(v.begin(), v.end(), s) != v.end();
  };
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a.size() > 1 && a[0] == '-' && !(a.size() > 1 && (std::isdigit((unsigned char)a[1]) || a[1] == '.'))) {
      if (contains(valueFlags, a)) {
        if (i + 1 >= args.size()) fail(Code::InvalidArgument, Stage::Api, "option " + a + " needs a value");
        out.flags.emplace_back(a, args[++i]);
      } else if (contains(switches, a)) {
        out.flags.emplace_back(a, "");
      } else {
        fail(Code::InvalidArgument, Stage::Api, "unknown option " + a);
      }
    } else {
      out.positional.push_back(a);
    }
  }
  return out;
}

Args parseArgs(const std::vector<std::string>& args, const std::vector<Flag>& flags) {
  std::vector<std::string> valueFlags, switches;
  for (const Flag& f : flags) (f.value.empty() ? switches : valueFlags).push_back(f.name);
  return parseArgs(args, valueFlags, switches);
}

bool asksForHelp(const std::vector<std::string>& args, const std::vector<Flag>& flags) {
  for (size_t i = 0; i < args.size(); ++i) {
    if (args[i] == "--help" || args[i] == "-h") return true;
    for (const Flag& f : flags)
      if (args[i] == f.name && !f.value.empty()) ++i;  // its value, whatever it looks like
  }
  return false;
}

std::string helpText(const std::string& usage, const std::string& summary, const std::vector<Flag>& flags) {
  std::string s = "usage: conformesh " + usage + "\n\n" + summary + "\n\noptions:\n";
  // the flag in a column of 30, its text wrapped at 100 columns
  const size_t indent = 30, width = 100;
  auto line = [&](const std::string& left, const std::string& text) {
    std::string l = "  " + left;
    l += l.size() < indent ? std::string(indent - l.size(), ' ') : "\n" + std::string(indent, ' ');
    size_t column = indent, start = 0;
    while (start < text.size()) {
      size_t end = text.find(' ', start);
      if (end == std::string::npos) end = text.size();
      const std::string word = text.substr(start, end - start);
      if (column > indent && column + 1 + word.size() > width) {
        l += "\n" + std::string(indent, ' ');
        column = indent;
      }
      if (column > indent) l += ' ', ++column;
      l += word;
      column += word.size();
      start = end + 1;
    }
    s += l + "\n";
  };
  for (const Flag& f : flags)
    line(f.name + (f.value.empty() ? "" : " " + f.value), f.help + (f.fallback.empty() ? "" : " (default " + f.fallback + ")"));
  line("-h, --help", "print this help and exit");
  return s;
}

std::vector<uint8_t> readFileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(Code::IoError, Stage::Read, "cannot open '" + path + "': " + std::strerror(errno));
  std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) fail(Code::IoError, Stage::Read, "error while reading '" + path + "'");
  return bytes;
}

void writeFileBytes(const std::string& path, const std::vector<uint8_t>& bytes) {
  std::ofstream out(path, std::ios::binary);
  if (!out) fail(Code::IoError, Stage::Write, "cannot create '" + path + "': " + std::strerror(errno));
  out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
  if (!out) fail(Code::IoError, Stage::Write, "error while writing '" + path + "'");
}

std::string jsonString(const std::string& s) {
  std::string o = "\"";
  for (unsigned char c : s) {
    switch (c) {
      case '"': o += "\\\""; break;
      case '\\': o += "\\\\"; break;
      case '\n': o += "\\n"; break;
      case '\r': o += "\\r"; break;
      case '\t': o += "\\t"; break;
      default:
        if (c < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", c);
          o += buf;
        } else {
          o += char(c);
        }
    }
  }
  return o + "\"";
}

std::string jsonNumber(double v) {
  if (!std::isfinite(v)) return "null";
  char buf[40];
  // Integers print as integers ("9000", not %g's "9e+03").
  if (v == std::floor(v) && std::fabs(v) < 9007199254740992.0) {
    std::snprintf(buf, sizeof buf, "%.0f", v == 0 ? 0.0 : v);
    return buf;
  }
  for (int prec = 1; prec <= 17; ++prec) {
    std::snprintf(buf, sizeof buf, "%.*g", prec, v);
    if (std::strtod(buf, nullptr) == v) break;
  }
  return buf;
}

int reportError(const Status& s, bool json) {
  if (json) {
    std::printf("{\"error\":{\"code\":%d,\"name\":%s,\"stage\":%s,\"message\":%s}}\n", int(s.code),
                jsonString(codeName(s.code)).c_str(), jsonString(stageName(s.stage)).c_str(),
                jsonString(s.message).c_str());
  } else {
    std::fprintf(stderr, "conformesh: %s (%s, stage %s)\n", s.message.c_str(), codeName(s.code),
                 stageName(s.stage));
  }
  return 1;
}

conformal::BoundaryCondition boundaryFlag(const Args& args, const char* fallback) {
  conformal::BoundaryCondition b{};
  if (!parseBoundary(args.get("--boundary", fallback), b))
    fail(Code::InvalidArgument, Stage::Api, "--boundary must be circle, free or corners");
  return b;
}

const char* boundaryFlagValue(conformal::BoundaryCondition b) { return boundaryKey(b); }

}  // namespace conformesh::cli
