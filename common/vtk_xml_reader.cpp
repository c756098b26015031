// Strict VTK XML PolyData reader for the points file (see vtk_xml_reader.hpp for why it exists).
// Two layers: a small XML parser for the element tree (the appended raw block is located, not
// parsed), then the array decoder that checks every offset and size against the file.
#include "common/vtk_xml_reader.hpp"

#include <vtkCommand.h>
#include <vtkNew.h>
#include <vtkZLibDataCompressor.h>

#include <algorithm>
#include <bit>
#include <charconv>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <string_view>
#include <utility>

#include "common/input_error.hpp"

namespace mppm {
namespace {

[[noreturn]] void fail(const std::string& path, const std::string& problem) { throw InputError(path + ": " + problem); }

// ---------------------------------------------------------------------------------------------
// XML layer

struct XmlElement {
  std::string name;
  std::vector<std::pair<std::string, std::string>> attributes;
  std::vector<XmlElement> children;
  std::string text;  // character data directly inside this element (not inside children)
  std::size_t line = 0;
  // Only for <AppendedData>: the bytes after the '_' marker, up to </AppendedData>.
  std::size_t raw_begin = 0, raw_end = 0;

  const std::string* attribute(std::string_view key) const {
    for (const auto& [k, v] : attributes)
      if (k == key) return &v;
    return nullptr;
  }
};

// Real points files nest 6 deep; the limit keeps a hostile file from exhausting the stack.
constexpr int kMaxXmlDepth = 32;

class XmlParser {
 public:
  XmlParser(const std::string& bytes, const std::string& path) : s_(bytes), path_(path) {}

  XmlElement parse_document() {
    if (s_.empty())
      fail(path_, "empty file: not a VTK XML PolyData file (expected POINTS.vtp written by mppm-preprocess)");
    if (s_.compare(0, 3, "\xEF\xBB\xBF") == 0) pos_ = 3;  // UTF-8 byte order mark
    skip_misc();
    if (!starts_with("<") || starts_with("</"))
      fail(path_,
           "not a VTK XML PolyData file (no XML element at the start; expected POINTS.vtp written by mppm-preprocess)");
    XmlElement root = parse_element(0);
    skip_misc();
    if (pos_ != s_.size()) error("unexpected content after the closing </" + root.name + ">");
    return root;
  }

 private:
  [[noreturn]] void error(const std::string& problem) const {
    const auto line =
        1 + std::count(s_.begin(), s_.begin() + static_cast<std::ptrdiff_t>(std::min(pos_, s_.size())), '\n');
    fail(path_, "malformed XML at line " + std::to_string(line) + ": " + problem);
  }
  bool starts_with(std::string_view prefix) const { return s_.compare(pos_, prefix.size(), prefix) == 0; }
  bool at_end() const { return pos_ >= s_.size(); }
  static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }
  static bool is_name_start(char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || c == '_' || c == ':'; }
  static bool is_name_char(char c) { return is_name_start(c) || (c >= '0' && c <= '9') || c == '-' || c == '.'; }
  void skip_spaces() {
    while (!at_end() && is_space(s_[pos_])) ++pos_;
  }
  void skip_past(std::string_view terminator, const char* what) {
    const std::size_t end = s_.find(terminator, pos_);
    if (end == std::string::npos) error(std::string("unterminated ") + what);
    pos_ = end + terminator.size();
  }
  // Spaces, comments, processing instructions (<?xml ...?>) between elements.
  void skip_misc() {
    for (;;) {
      skip_spaces();
      if (starts_with("<!--"))
        skip_past("-->", "comment");
      else if (starts_with("<?"))
        skip_past("?>", "processing instruction");
      else if (starts_with("<!"))
        error("document type declarations are not supported");
      else
        return;
    }
  }
  std::string read_name() {
    if (at_end() || !is_name_start(s_[pos_])) error("expected a name");
    const std::size_t begin = pos_;
    while (!at_end() && is_name_char(s_[pos_])) ++pos_;
    return s_.substr(begin, pos_ - begin);
  }
  // Appends the character data up to `end`, resolving the predefined and numeric entities.
  void append_decoded(std::string& out, std::size_t end) {
    while (pos_ < end) {
      const char c = s_[pos_];
      if (c != '&') {
        out += c;
        ++pos_;
        continue;
      }
      const std::size_t semicolon = s_.find(';', pos_);
      if (semicolon == std::string::npos || semicolon > end || semicolon - pos_ > 10) error("bad entity reference");
      const std::string_view entity(s_.data() + pos_ + 1, semicolon - pos_ - 1);
      if (entity == "lt")
        out += '<';
      else if (entity == "gt")
        out += '>';
      else if (entity == "amp")
        out += '&';
      else if (entity == "quot")
        out += '"';
      else if (entity == "apos")
        out += '\'';
      else if (entity.size() > 1 && entity[0] == '#') {
        const bool hex = entity[1] == 'x';
        unsigned code = 0;
        const char* first = entity.data() + (hex ? 2 : 1);
        const char* last = entity.data() + entity.size();
        const auto [ptr, ec] = std::from_chars(first, last, code, hex ? 16 : 10);
        if (ec != std::errc() || ptr != last || first == last || code == 0 || code > 127)
          error("unsupported character reference &" + std::string(entity) + ";");
        out += static_cast<char>(code);
      } else {
        error("unknown entity &" + std::string(entity) + ";");
      }
      pos_ = semicolon + 1;
    }
  }
  void parse_attributes(XmlElement& element) {
    for (;;) {
      const std::size_t before = pos_;
      skip_spaces();
      if (at_end()) error("file ends inside the tag <" + element.name + ">");
      if (s_[pos_] == '>' || starts_with("/>")) return;
      if (pos_ == before) error("expected a space before the attribute of <" + element.name + ">");
      std::string key = read_name();
      skip_spaces();
      if (at_end() || s_[pos_] != '=') error("expected '=' after attribute '" + key + "'");
      ++pos_;
      skip_spaces();
      if (at_end() || (s_[pos_] != '"' && s_[pos_] != '\''))
        error("expected a quoted value for attribute '" + key + "'");
      const char quote = s_[pos_++];
      const std::size_t close = s_.find(quote, pos_);
      if (close == std::string::npos) error("unterminated value of attribute '" + key + "'");
      if (s_.find('<', pos_) < close) error("'<' inside the value of attribute '" + key + "'");
      std::string value;
      append_decoded(value, close);
      pos_ = close + 1;
      if (element.attribute(key)) error("attribute '" + key + "' given twice in <" + element.name + ">");
      element.attributes.emplace_back(std::move(key), std::move(value));
    }
  }
  // The raw appended block may contain any byte, '<' included: it ends at the last
  // </AppendedData> of the file (what VTK writes: the block, a newline, the end tag).
  void locate_appended_block(XmlElement& element) {
    skip_spaces();
    if (at_end() || s_[pos_] != '_') error("<AppendedData> does not start with the '_' marker");
    element.raw_begin = ++pos_;
    const std::size_t end = s_.rfind("</AppendedData");
    if (end == std::string::npos || end < element.raw_begin) error("file ends inside <AppendedData> (truncated file?)");
    element.raw_end = end;
    pos_ = end;
  }
  XmlElement parse_element(int depth) {
    if (depth > kMaxXmlDepth) error("elements nested more than " + std::to_string(kMaxXmlDepth) + " deep");
    XmlElement element;
    element.line =
        static_cast<std::size_t>(1 + std::count(s_.begin(), s_.begin() + static_cast<std::ptrdiff_t>(pos_), '\n'));
    ++pos_;  // '<'
    element.name = read_name();
    parse_attributes(element);
    if (starts_with("/>")) {
      pos_ += 2;
      return element;
    }
    ++pos_;  // '>'
    if (element.name == "AppendedData") {
      const std::string* encoding = element.attribute("encoding");
      if (encoding && *encoding == "raw") locate_appended_block(element);
    }
    for (;;) {
      if (at_end()) error("file ends inside <" + element.name + "> (truncated file?)");
      if (starts_with("</")) {
        pos_ += 2;
        const std::string closing = read_name();
        if (closing != element.name) error("</" + closing + "> closes <" + element.name + ">");
        skip_spaces();
        if (at_end() || s_[pos_] != '>') error("expected '>' after </" + closing);
        ++pos_;
        return element;
      }
      if (starts_with("<!--"))
        skip_past("-->", "comment");
      else if (starts_with("<![CDATA[")) {
        pos_ += 9;
        const std::size_t end = s_.find("]]>", pos_);
        if (end == std::string::npos) error("unterminated CDATA section");
        element.text.append(s_, pos_, end - pos_);
        pos_ = end + 3;
      } else if (starts_with("<?"))
        skip_past("?>", "processing instruction");
      else if (s_[pos_] == '<')
        element.children.push_back(parse_element(depth + 1));
      else {
        const std::size_t next = std::min(s_.find('<', pos_), s_.size());
        append_decoded(element.text, next);
      }
    }
  }

  const std::string& s_;
  const std::string& path_;
  std::size_t pos_ = 0;
};

// ---------------------------------------------------------------------------------------------
// Array layer

struct FileFormat {
  bool swap_bytes = false;  // file byte order differs from this machine's
  int header_bytes = 4;     // UInt32 or UInt64 block headers
  bool zlib = false;
  const XmlElement* appended = nullptr;
};

// Bytes per value of the numeric VTK types; 0 for unknown.
int type_size(std::string_view type) {
  if (type == "Int8" || type == "UInt8") return 1;
  if (type == "Int16" || type == "UInt16") return 2;
  if (type == "Int32" || type == "UInt32" || type == "Float32") return 4;
  if (type == "Int64" || type == "UInt64" || type == "Float64") return 8;
  return 0;
}

template <typename T>
T load(const unsigned char* bytes, bool swap) {
  unsigned char buffer[sizeof(T)];
  std::memcpy(buffer, bytes, sizeof(T));
  if (swap) std::reverse(buffer, buffer + sizeof(T));
  T value;
  std::memcpy(&value, buffer, sizeof(T));
  return value;
}

// The values of one type at `p`, as doubles, into `out` (its size is their count).
template <typename T>
void load_all(const unsigned char* p, bool swap, std::vector<double>& out) {
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = static_cast<double>(load<T>(p + i * sizeof(T), swap));
}

// The type is matched once per array: matched per value, its names' comparisons took 7 % of
// reading the 3-D benchmark block's points file.
void load_numbers(std::string_view type, const unsigned char* p, bool swap, std::vector<double>& out) {
  if (type == "Int8") return load_all<std::int8_t>(p, swap, out);
  if (type == "UInt8") return load_all<std::uint8_t>(p, swap, out);
  if (type == "Int16") return load_all<std::int16_t>(p, swap, out);
  if (type == "UInt16") return load_all<std::uint16_t>(p, swap, out);
  if (type == "Int32") return load_all<std::int32_t>(p, swap, out);
  if (type == "UInt32") return load_all<std::uint32_t>(p, swap, out);
  if (type == "Int64") return load_all<std::int64_t>(p, swap, out);
  if (type == "UInt64") return load_all<std::uint64_t>(p, swap, out);
  if (type == "Float32") return load_all<float>(p, swap, out);
  load_all<double>(p, swap, out);  // Float64 (type_size() has vetted the name)
}

// More values than this per array is not a points file but a corrupted size (and the products
// below stay far from overflow).
constexpr std::int64_t kMaxValues = std::int64_t{1} << 40;
// deflate cannot compress better than 1032:1, so a block header that promises more output than
// that from the compressed bytes present is corrupt; checked before anything is allocated.
constexpr std::uint64_t kMaxDeflateRatio = 1032;

// Collects the zlib wrapper's error instead of letting VTK print it.
class ErrorCollector : public vtkCommand {
 public:
  static ErrorCollector* New() { return new ErrorCollector; }
  void Execute(vtkObject*, unsigned long, void* data) override {
    if (message.empty() && data) message = static_cast<const char*>(data);
  }
  std::string message;
};

class ArrayDecoder {
 public:
  ArrayDecoder(const std::string& bytes, const std::string& path, const FileFormat& format)
      : s_(bytes), path_(path), format_(format) {}

  // `expected_tuples` < 0: take NumberOfTuples from the element (field data).
  VtkArray decode(const XmlElement& e, std::int64_t expected_tuples, const std::string& where) {
    VtkArray array;
    const std::string* name = e.attribute("Name");
    array.name = name ? *name : "";
    const std::string label = where + " array '" + array.name + "' (line " + std::to_string(e.line) + ")";
    const std::string* type = e.attribute("type");
    if (!type) fail(path_, label + " has no type");
    array.type = *type;
    if (!array.is_string() && type_size(array.type) == 0)
      fail(path_, label + " has unknown or unsupported type '" + array.type + "'");
    array.components = static_cast<int>(integer_attribute(e, "NumberOfComponents", 1, 1, 64, label));
    const std::string* tuples_text = e.attribute("NumberOfTuples");
    if (expected_tuples < 0 && !tuples_text) fail(path_, label + " has no NumberOfTuples");
    array.tuples = tuples_text ? integer_attribute(e, "NumberOfTuples", 0, 0, kMaxValues, label) : expected_tuples;
    if (expected_tuples >= 0 && array.tuples != expected_tuples)
      fail(path_, label + " has " + std::to_string(array.tuples) + " tuples (expected " +
                      std::to_string(expected_tuples) + ", one per point)");
    if (array.tuples > kMaxValues / array.components) fail(path_, label + " is impossibly large");
    const std::int64_t values = array.tuples * array.components;

    const std::string* format = e.attribute("format");
    if (!format) fail(path_, label + " has no format");
    if (*format == "ascii") {
      decode_ascii(e, array, values, label);
    } else if (*format == "appended") {
      if (array.type == "Float64" && !format_.swap_bytes) {
        // Already this machine's doubles: unpacked straight into the array, without a buffer of
        // bytes and a conversion, each a first write to fresh memory (reading the 3-D benchmark
        // block's points: 0.098-0.119 s -> 0.082-0.102 s, 4 runs each taking turns).
        appended_bytes(e, array, values, label, &array.numbers);
      } else {
        const std::string bytes = appended_bytes(e, array, values, label, nullptr);
        decode_binary(bytes, array, values, label);
      }
    } else if (*format == "binary") {
      fail(path_, label +
                      ": format 'binary' (inline base64) is not supported; write the file with "
                      "appended raw data or ascii, as mppm-preprocess does");
    } else {
      fail(path_, label + " has unknown format '" + *format + "'");
    }
    return array;
  }

 private:
  std::int64_t integer_attribute(const XmlElement& e, const char* key, std::int64_t fallback, std::int64_t min,
                                 std::int64_t max, const std::string& label) {
    const std::string* text = e.attribute(key);
    if (!text) return fallback;
    std::int64_t value = 0;
    const char* last = text->data() + text->size();
    const auto [ptr, ec] = std::from_chars(text->data(), last, value);
    if (ec != std::errc() || ptr != last || text->empty() || value < min || value > max)
      fail(path_, label + ": " + key + "=\"" + *text + "\" is not an integer in " + std::to_string(min) + ".." +
                      std::to_string(max));
    return value;
  }

  void decode_ascii(const XmlElement& e, VtkArray& array, std::int64_t values, const std::string& label) {
    const std::string& text = e.text;
    const bool integer = array.is_string() || array.type.find("Int") != std::string::npos;
    std::string current;  // String arrays: the characters of the string being read
    std::int64_t count = 0;
    std::size_t pos = 0;
    // Reserve no more than the text can hold (two characters per value at least).
    if (!array.is_string())
      array.numbers.reserve(
          static_cast<std::size_t>(std::min<std::int64_t>(values, static_cast<std::int64_t>(text.size() / 2 + 1))));
    for (;;) {
      while (pos < text.size() && (text[pos] == ' ' || text[pos] == '\t' || text[pos] == '\n' || text[pos] == '\r'))
        ++pos;
      if (pos >= text.size()) break;
      std::size_t end = pos;
      while (end < text.size() && text[end] != ' ' && text[end] != '\t' && text[end] != '\n' && text[end] != '\r')
        ++end;
      const char* first = text.data() + pos;
      const char* last = text.data() + end;
      double value = 0;
      bool ok = false;
      if (integer) {
        std::int64_t v = 0;
        const auto [ptr, ec] = std::from_chars(first, last, v);
        ok = ec == std::errc() && ptr == last;
        value = static_cast<double>(v);
      } else {
        const auto [ptr, ec] = std::from_chars(first, last, value);
        ok = ec == std::errc() && ptr == last;
      }
      if (!ok)
        fail(path_, label + ": \"" + std::string(first, std::min<std::size_t>(end - pos, 40)) + "\" is not " +
                        (integer ? "an integer" : "a number"));
      if (array.is_string()) {
        if (value < 0 || value > 255)
          fail(path_,
               label + ": character code " + std::to_string(static_cast<std::int64_t>(value)) + " out of 0..255");
        if (value == 0) {
          if (static_cast<std::int64_t>(array.strings.size()) == values)
            fail(path_, label + " holds more than " + std::to_string(values) + " strings");
          array.strings.push_back(std::move(current));
          current.clear();
        } else {
          current += static_cast<char>(static_cast<unsigned char>(value));
        }
      } else {
        if (count == values) fail(path_, label + " holds more than " + std::to_string(values) + " values");
        array.numbers.push_back(value);
      }
      ++count;
      pos = end;
    }
    if (array.is_string()) {
      if (!current.empty()) fail(path_, label + ": the last string has no terminating 0");
      if (static_cast<std::int64_t>(array.strings.size()) != values)
        fail(path_, label + " holds " + std::to_string(array.strings.size()) + " strings (expected " +
                        std::to_string(values) + ")");
    } else if (count != values) {
      fail(path_, label + " holds " + std::to_string(count) + " values (expected " + std::to_string(values) + ")");
    }
  }

  std::uint64_t header_value(std::size_t at) const {
    const auto* p = reinterpret_cast<const unsigned char*>(s_.data()) + at;
    return format_.header_bytes == 8 ? load<std::uint64_t>(p, format_.swap_bytes)
                                     : load<std::uint32_t>(p, format_.swap_bytes);
  }

  // The array's bytes from the appended block, decompressed, every header checked against the
  // block's extent before use (and before anything is allocated). With `direct` (a Float64 array
  // in this machine's byte order) they go into its `values` doubles instead, and the string
  // returned is empty.
  std::string appended_bytes(const XmlElement& e, const VtkArray& array, std::int64_t values, const std::string& label,
                             std::vector<double>* direct) {
    if (!format_.appended)
      fail(path_, label + " is 'appended' but the file has no <AppendedData encoding=\"raw\"> block");
    const std::size_t begin = format_.appended->raw_begin;
    const std::uint64_t block = format_.appended->raw_end - begin;
    const std::int64_t offset = integer_attribute(e, "offset", -1, 0, std::numeric_limits<std::int64_t>::max(), label);
    if (offset < 0) fail(path_, label + " has no offset");
    const auto h = static_cast<std::uint64_t>(format_.header_bytes);
    const auto at = static_cast<std::uint64_t>(offset);
    auto need = [&](std::uint64_t from, std::uint64_t size, const char* what) {
      if (from > block || size > block - from)
        fail(path_, label + ": " + what + " at offset " + std::to_string(from) + " (+" + std::to_string(size) +
                        " bytes) runs past the end of the appended data (" + std::to_string(block) +
                        " bytes; truncated or corrupted file)");
    };
    const std::uint64_t expected_bytes =
        array.is_string() ? 0 : static_cast<std::uint64_t>(values) * static_cast<std::uint64_t>(type_size(array.type));
    auto check_size = [&](std::uint64_t size) {
      if (!array.is_string() && size != expected_bytes)
        fail(path_, label + " holds " + std::to_string(size) + " bytes (expected " + std::to_string(values) +
                        " values x " + std::to_string(type_size(array.type)) +
                        " bytes = " + std::to_string(expected_bytes) + ")");
    };

    if (!format_.zlib) {
      need(at, h, "the size header");
      const std::uint64_t size = header_value(begin + at);
      check_size(size);
      need(at + h, size, "the data");
      if (direct) {
        direct->resize(static_cast<std::size_t>(values));
        if (size > 0) std::memcpy(direct->data(), s_.data() + begin + at + h, size);
        return {};
      }
      return s_.substr(begin + at + h, size);
    }

    // Compressed: [block count, block size, size of the last block, compressed size of each].
    need(at, 3 * h, "the compression header");
    const std::uint64_t blocks = header_value(begin + at);
    const std::uint64_t block_size = header_value(begin + at + h);
    const std::uint64_t last_size = header_value(begin + at + 2 * h);
    if (blocks > (block - at) / h)
      fail(path_, label + ": corrupted compression header (" + std::to_string(blocks) + " blocks)");
    need(at + 3 * h, blocks * h, "the compressed block sizes");
    if (blocks > 0 && (block_size == 0 || block_size > (std::uint64_t{1} << 32) || last_size > block_size))
      fail(path_, label + ": corrupted compression header (block size " + std::to_string(block_size) + ", last block " +
                      std::to_string(last_size) + ")");
    const std::uint64_t final_block = last_size == 0 ? block_size : last_size;
    const std::uint64_t total = blocks == 0 ? 0 : (blocks - 1) * block_size + final_block;
    check_size(total);
    std::uint64_t compressed_total = 0;
    std::vector<std::uint64_t> compressed(blocks);
    for (std::uint64_t b = 0; b < blocks; ++b) {
      compressed[b] = header_value(begin + at + (3 + b) * h);
      if (compressed[b] > block)
        fail(path_, label + ": corrupted compression header (block " + std::to_string(b) + " size)");
      compressed_total += compressed[b];
      if (compressed_total > block) need(at + (3 + blocks) * h, compressed_total, "the compressed data");
    }
    const std::uint64_t data_at = at + (3 + blocks) * h;
    need(data_at, compressed_total, "the compressed data");
    if (total > kMaxDeflateRatio * compressed_total + 64 * blocks)
      fail(path_, label + ": corrupted compression header (" + std::to_string(total) + " bytes from " +
                      std::to_string(compressed_total) + " compressed bytes)");

    std::string out(direct ? 0 : total, '\0');
    if (direct) direct->resize(static_cast<std::size_t>(values));
    unsigned char* const target =
        direct ? reinterpret_cast<unsigned char*>(direct->data()) : reinterpret_cast<unsigned char*>(out.data());
    vtkNew<vtkZLibDataCompressor> zlib;
    vtkNew<ErrorCollector> errors;
    zlib->AddObserver(vtkCommand::ErrorEvent, errors);
    std::uint64_t in = data_at, produced = 0;
    for (std::uint64_t b = 0; b < blocks; ++b) {
      const std::uint64_t want = b + 1 == blocks ? final_block : block_size;
      const std::size_t got = compressed[b] == 0
                                  ? 0
                                  : zlib->Uncompress(reinterpret_cast<const unsigned char*>(s_.data()) + begin + in,
                                                     compressed[b], target + produced, want);
      if (got != want)
        fail(path_, label + ": compressed block " + std::to_string(b) + " is corrupted (zlib: " +
                        (errors->message.empty() ? std::string("wrong size") : errors->message) + ")");
      in += compressed[b];
      produced += want;
    }
    return out;
  }

  void decode_binary(const std::string& bytes, VtkArray& array, std::int64_t values, const std::string& label) {
    if (array.is_string()) {
      std::size_t pos = 0;
      while (pos < bytes.size()) {
        const std::size_t end = bytes.find('\0', pos);
        if (end == std::string::npos) fail(path_, label + ": the last string has no terminating 0");
        if (static_cast<std::int64_t>(array.strings.size()) == values)
          fail(path_, label + " holds more than " + std::to_string(values) + " strings");
        array.strings.push_back(bytes.substr(pos, end - pos));
        pos = end + 1;
      }
      if (static_cast<std::int64_t>(array.strings.size()) != values)
        fail(path_, label + " holds " + std::to_string(array.strings.size()) + " strings (expected " +
                        std::to_string(values) + ")");
      return;
    }
    array.numbers.resize(static_cast<std::size_t>(values));
    load_numbers(array.type, reinterpret_cast<const unsigned char*>(bytes.data()), format_.swap_bytes, array.numbers);
  }

  const std::string& s_;
  const std::string& path_;
  const FileFormat& format_;
};

const XmlElement* only_child(const XmlElement& parent, std::string_view name, bool required, const std::string& path) {
  const XmlElement* found = nullptr;
  for (const XmlElement& child : parent.children) {
    if (child.name != name) continue;
    if (found)
      fail(path, "more than one <" + std::string(name) + "> in <" + parent.name + "> (line " +
                     std::to_string(child.line) + ")");
    found = &child;
  }
  if (required && !found)
    fail(path, "<" + parent.name + "> (line " + std::to_string(parent.line) + ") has no <" + std::string(name) + ">");
  return found;
}

std::vector<VtkArray> decode_arrays(const XmlElement* section, std::int64_t tuples, const std::string& where,
                                    ArrayDecoder& decoder, const std::string& path) {
  std::vector<VtkArray> arrays;
  if (!section) return arrays;
  for (const XmlElement& child : section->children) {
    if (child.name != "DataArray" && child.name != "Array") continue;
    VtkArray array = decoder.decode(child, tuples, where);
    for (const VtkArray& earlier : arrays)
      if (earlier.name == array.name) fail(path, "two " + where + " arrays named '" + array.name + "'");
    arrays.push_back(std::move(array));
  }
  return arrays;
}

const VtkArray* find_array(const std::vector<VtkArray>& arrays, const std::string& name) {
  for (const VtkArray& a : arrays)
    if (a.name == name) return &a;
  return nullptr;
}

std::string file_contents(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot open the points file");
  std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) fail(path, "read error");
  return bytes;
}

}  // namespace

const VtkArray* VtkPolyDataArrays::field(const std::string& name) const { return find_array(field_data, name); }
const VtkArray* VtkPolyDataArrays::point(const std::string& name) const { return find_array(point_data, name); }

VtkPolyDataArrays read_vtk_polydata_arrays(const std::string& path) {
  const std::string bytes = file_contents(path);
  const XmlElement root = XmlParser(bytes, path).parse_document();
  if (root.name != "VTKFile")
    fail(path, "not a VTK XML PolyData file (root element <" + root.name + ">, expected <VTKFile>)");
  const std::string* type = root.attribute("type");
  if (!type || *type != "PolyData")
    fail(path, "not a VTK XML PolyData file (VTKFile type '" + (type ? *type : std::string()) +
                   "'; expected POINTS.vtp written by mppm-preprocess)");

  FileFormat format;
  const std::string* order = root.attribute("byte_order");
  const bool little = std::endian::native == std::endian::little;
  if (order && *order == "BigEndian")
    format.swap_bytes = little;
  else if (order && *order == "LittleEndian")
    format.swap_bytes = !little;
  else if (order)
    fail(path, "unknown byte_order '" + *order + "'");
  const std::string* header = root.attribute("header_type");
  if (header && *header == "UInt64")
    format.header_bytes = 8;
  else if (header && *header != "UInt32")
    fail(path, "unknown header_type '" + *header + "' (expected UInt32 or UInt64)");
  const std::string* compressor = root.attribute("compressor");
  if (compressor && *compressor == "vtkZLibDataCompressor")
    format.zlib = true;
  else if (compressor && !compressor->empty())
    fail(path, "unsupported compressor '" + *compressor + "' (expected vtkZLibDataCompressor or none)");
  format.appended = only_child(root, "AppendedData", false, path);
  if (format.appended) {
    const std::string* encoding = format.appended->attribute("encoding");
    if (!encoding || *encoding != "raw")
      fail(path, "<AppendedData> encoding '" + (encoding ? *encoding : std::string()) +
                     "' is not supported (expected raw, as mppm-preprocess writes)");
  }

  const XmlElement* poly = only_child(root, "PolyData", true, path);
  const XmlElement* piece = only_child(*poly, "Piece", true, path);
  ArrayDecoder decoder(bytes, path, format);
  VtkPolyDataArrays result;
  const std::string* points_text = piece->attribute("NumberOfPoints");
  if (!points_text) fail(path, "<Piece> has no NumberOfPoints");
  {
    const char* last = points_text->data() + points_text->size();
    const auto [ptr, ec] = std::from_chars(points_text->data(), last, result.point_count);
    if (ec != std::errc() || ptr != last || points_text->empty() || result.point_count < 0 ||
        result.point_count > kMaxValues)
      fail(path, "<Piece> NumberOfPoints=\"" + *points_text + "\" is not a point count");
  }
  result.field_data = decode_arrays(only_child(*poly, "FieldData", false, path), -1, "field data", decoder, path);
  result.point_data =
      decode_arrays(only_child(*piece, "PointData", false, path), result.point_count, "point", decoder, path);
  const XmlElement* points = only_child(*piece, "Points", true, path);
  std::vector<VtkArray> coordinates = decode_arrays(points, result.point_count, "Points", decoder, path);
  if (coordinates.size() != 1)
    fail(path, "<Points> must hold exactly one array (it holds " + std::to_string(coordinates.size()) + ")");
  result.points = std::move(coordinates.front());
  if (result.points.is_string() || result.points.components != 3)
    fail(path, "the point coordinates must be a numeric array with 3 components");
  return result;
}

}  // namespace mppm
