// conformesh — internals shared by the mesh readers and writers (not a public header).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include "core/status.h"
#include "mesh/mesh_io.h"

namespace conformesh::io_detail {

//! The bytes being read and the name used as a message prefix.
struct Source {
  const uint8_t* data = nullptr;
  size_t size = 0;
  std::string name;  //!< file name or format name
  bool forced = false;  //!< the format was given by the caller or the extension, not detected

  std::string prefix() const { return name.empty() ? std::string() : name + ": "; }
  [[noreturn]] void failLine(Code code, size_t line, const std::string& msg) const {
    fail(code, Stage::Read, prefix() + "line " + std::to_string(line) + ": " + msg);
  }
  [[noreturn]] void failOffset(Code code, uint64_t offset, const std::string& msg) const {
    fail(code, Stage::Read, prefix() + "byte offset " + std::to_string(offset) + ": " + msg);
  }
  [[noreturn]] void failPlain(Code code, const std::string& msg) const {
    fail(code, Stage::Read, prefix() + msg);
  }
};

//! Largest vertex count a MeshBuffers can index (uint32 indices, one value kept spare).
constexpr uint64_t kMaxVertices = 0xFFFFFFFEull;

inline bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

//! Parse a decimal floating-point token [b, e) entirely. Exact (correctly rounded): a fast path
//! for <= 19 significant digits and |exponent| <= 22 (Clinger 1990, "How to read floating point
//! numbers accurately"), else strtod. Accepts "nan", "inf" (they come back non-finite).
//! Returns false when the token is not a number.
bool parseDouble(const char* b, const char* e, double& out);
//! Parse a decimal integer token [b, e) entirely (optional sign). False if not an integer or if
//! |value| > 2^62.
bool parseInt(const char* b, const char* e, int64_t& out);

//! Whitespace-separated tokens over text, counting lines; optional comment character that hides
//! the rest of its line.
class TextScanner {
 public:
  TextScanner(const char* begin, const char* end, char comment, size_t firstLine = 1)
      : p_(begin), end_(end), comment_(comment), line_(firstLine) {}

  //! Next token (across line ends); false at the end of the text.
  bool next(const char*& b, const char*& e) {
    skipSpaceAndComments(true);
    if (p_ >= end_) return false;
    b = p_;
    while (p_ < end_ && !isSpace(*p_) && *p_ != '\n' && *p_ != comment_char()) ++p_;
    e = p_;
    tokenLine_ = line_;
    return true;
  }
  //! Next token on the current line only; false at the line end (the newline is not consumed).
  bool nextOnLine(const char*& b, const char*& e) {
    skipSpaceAndComments(false);
    if (p_ >= end_ || *p_ == '\n') return false;
    return next(b, e);
  }
  //! Skip everything up to and including the next line end.
  void skipLine() {
    const void* nl = p_ < end_ ? std::memchr(p_, '\n', size_t(end_ - p_)) : nullptr;
    if (nl) {
      p_ = static_cast<const char*>(nl) + 1;
      ++line_;
    } else {
      p_ = end_;
    }
  }
  size_t line() const { return line_; }            //!< line of the read position
  size_t tokenLine() const { return tokenLine_; }  //!< line of the last token returned
  const char* pos() const { return p_; }
  size_t remaining() const { return size_t(end_ - p_); }

 private:
  char comment_char() const { return comment_ ? comment_ : '\n'; }
  void skipSpaceAndComments(bool crossLines) {
    while (p_ < end_) {
      char c = *p_;
      if (isSpace(c)) {
        ++p_;
      } else if (c == '\n') {
        if (!crossLines) return;
        ++p_;
        ++line_;
      } else if (comment_ && c == comment_) {
        while (p_ < end_ && *p_ != '\n') ++p_;
      } else {
        return;
      }
    }
  }

  const char* p_;
  const char* end_;
  char comment_;
  size_t line_;
  size_t tokenLine_ = 0;
};

//! Exact weld of a triangle soup given as 9 coordinates per triangle (STL): equal positions
//! (same bits, -0 == +0) become one vertex, numbered by first appearance. Fills mesh.positions and
//! mesh.triangles.
void weldSoupExact(const std::vector<double>& soup, MeshBuffers& mesh);
//! The same for binary STL records (50 bytes each, vertices at bytes 12..47 as float32), read in
//! place. Calls nonFinite(triangle, value 0..8) for a NaN / infinite value (it must throw).
void weldBinaryStlRecords(const uint8_t* records, size_t triangles, MeshBuffers& mesh,
                          const std::function<void(size_t, int)>& nonFinite);

//! Content checks used by detectFormat (they look at the first few KB only).
bool looksLikeOff(const uint8_t* data, size_t size);
bool looksLikeObj(const uint8_t* data, size_t size);

//! Readers. Each fills result.mesh (positions, triangles, maybe uvs) and result.format.
void readObj(const Source& src, const ReadOptions& opt, ReadResult& result);
void readOff(const Source& src, const ReadOptions& opt, ReadResult& result);
void readStlAscii(const Source& src, const ReadOptions& opt, ReadResult& result);
void readStlBinary(const Source& src, const ReadOptions& opt, ReadResult& result);
void readPly(const Source& src, const ReadOptions& opt, ReadResult& result);

//! Longest text formatDouble writes.
constexpr size_t kMaxDoubleChars = 40;
//! Write finite `v` as the shortest of 15, 16 or 17 significant digits that parses back to
//! exactly `v` (fixed notation for 1e-5 <= |v| < 1e16, else scientific); returns the length.
//! Throws Error(NonFiniteCoordinate, Write) for NaN / infinity.
size_t formatDouble(double v, char* out);
//! formatDouble appended to a string.
void appendDouble(std::string& out, double v);

}  // namespace conformesh::io_detail
