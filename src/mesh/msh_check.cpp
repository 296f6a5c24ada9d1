#include "mesh/msh_check.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <optional>
#include <set>
#include <utility>
#include <vector>

#include "config/text.hpp"
#include "mesh/mesh.hpp"

namespace snapjump::mesh {
namespace {

// gmsh 4.8 looks node tags up as an int.
constexpr std::int64_t kMaxNodeTag = INT_MAX;
constexpr std::int64_t kMaxTag = std::numeric_limits<std::int64_t>::max();
// gmsh reads an element's node tags from one line of at most 10,000 bytes and other lines in
// pieces of 1,024 (a physical name in 256): a longer line would not be read as it is here.
constexpr std::size_t kMaxElementLine = 9000, kMaxLine = 1000, kMaxNameLine = 250;

// gmsh's element types 1 to 31 (MSH_LIN_2 to MSH_TET_56): dimension and number of nodes.
constexpr std::array<MshElementType, 31> kTypes = {{
    {1, 2},  {2, 3},  {2, 4},  {3, 4}, {3, 8}, {3, 6},  {3, 5},  {1, 3},  {2, 6},  {2, 9},  {3, 10},
    {3, 27}, {3, 18}, {3, 14}, {0, 1}, {2, 8}, {3, 20}, {3, 15}, {3, 13}, {2, 9},  {2, 10}, {2, 12},
    {2, 15}, {2, 15}, {2, 21}, {1, 4}, {1, 5}, {1, 6},  {3, 20}, {3, 35}, {3, 56},
}};

// A short excerpt of the file (text::excerpt), in quotes.
std::string quoted(std::string_view s) { return fmt::format("\"{}\"", text::excerpt(s)); }

bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v';
}

// The next word of `s`, which moves past it; empty when none is left.
std::string_view next_word(std::string_view& s) {
  std::size_t a = 0;
  while (a < s.size() && is_space(s[a])) ++a;
  std::size_t b = a;
  while (b < s.size() && !is_space(s[b])) ++b;
  const auto word = s.substr(a, b - a);
  s.remove_prefix(b);
  return word;
}

// A whole word as a number, as gmsh's scanf would read it (a leading '+' allowed).
template <class T>
std::optional<T> to_number(std::string_view w) {
  if (w.size() > 1 && w[0] == '+' && w[1] != '-') w.remove_prefix(1);
  T v{};
  const auto [end, ec] = std::from_chars(w.data(), w.data() + w.size(), v);
  if (ec != std::errc() || end != w.data() + w.size()) return std::nullopt;
  return v;
}

// The file's bytes, read front to back, and what an error message needs: where the last thing
// read starts (its line, or its byte in binary data) and the section it is in.
class Reader {
 public:
  Reader(std::string_view bytes, const std::string& name) : text_(bytes), name_(name) {}

  [[noreturn]] void fail(const std::string& what) const { fail_at(mark_, what); }
  [[noreturn]] void fail_at(std::size_t pos, const std::string& what) const;
  [[noreturn]] void ends() const;
  void enter(std::string section, bool binary) {
    section_ = std::move(section);
    binary_ = binary;
  }
  const std::string& section() const { return section_; }
  std::size_t left() const { return text_.size() - pos_; }
  std::size_t mark() const { return mark_; }
  std::size_t pos_of(std::string_view part) const {
    return static_cast<std::size_t>(part.data() - text_.data());
  }
  bool skip_space() {
    while (pos_ < text_.size() && is_space(text_[pos_])) ++pos_;
    return pos_ < text_.size();
  }
  std::string_view line(std::size_t most = kMaxLine);
  std::string_view word();
  std::string_view bytes(std::size_t n);

 private:
  std::string_view text_;
  std::size_t pos_ = 0, mark_ = 0;
  std::string name_, section_;
  bool binary_ = false;
};

void Reader::fail_at(std::size_t pos, const std::string& what) const {
  std::string where;
  if (binary_) {
    where = fmt::format("byte {} (binary data of {})", pos, section_);
  } else {
    const auto line =
        std::count(text_.begin(), text_.begin() + static_cast<std::ptrdiff_t>(pos), '\n') + 1;
    where = section_.empty() ? fmt::format("line {}", line)
                             : fmt::format("line {} ({})", line, section_);
  }
  throw MeshError(fmt::format("{}: {}: {}", name_, where, what));
}

void Reader::ends() const {
  fail_at(text_.size(),
          section_.empty()
              ? std::string("the file ends too soon")
              : fmt::format("the file ends inside the {} section (cut short?)", section_));
}

// The next line without its end (\n or \r\n); fails at the end of the file.
std::string_view Reader::line(std::size_t most) {
  if (pos_ >= text_.size()) ends();
  mark_ = pos_;
  const auto end = std::min(text_.find('\n', pos_), text_.size());
  auto l = text_.substr(pos_, end - pos_);
  pos_ = std::min(end + 1, text_.size());
  if (!l.empty() && l.back() == '\r') l.remove_suffix(1);
  if (l.size() > most) {
    fail(fmt::format("a line of {} bytes, longer than gmsh reads in one piece ({} bytes): {}",
                     l.size(), most, quoted(l)));
  }
  return l;
}

// The next word, after any white space (line ends included); fails at the end of the file.
std::string_view Reader::word() {
  if (!skip_space()) ends();
  mark_ = pos_;
  while (pos_ < text_.size() && !is_space(text_[pos_])) ++pos_;
  return text_.substr(mark_, pos_ - mark_);
}

// The next n bytes; fails when the file ends before.
std::string_view Reader::bytes(std::size_t n) {
  mark_ = pos_;
  if (n > left()) ends();
  pos_ += n;
  return text_.substr(mark_, n);
}

// The numbers of a section: words in an ASCII file, or gmsh's binary values (size_t, int and
// double, in this machine's byte order, which the file's header confirmed).
class Values {
 public:
  Values(Reader& r, bool binary) : r_(r), binary_(binary) {}
  Reader& reader() { return r_; }
  bool binary() const { return binary_; }

  std::uint64_t count(std::string_view what) {
    if (binary_) return raw<std::uint64_t>();
    const auto w = r_.word();
    const auto v = to_number<std::uint64_t>(w);
    if (!v) r_.fail(fmt::format("{} must be a count (an integer from 0), not {}", what, quoted(w)));
    return *v;
  }
  std::int64_t integer(std::string_view what, std::int64_t lo, std::int64_t hi) {
    if (binary_) return in_range(raw<std::int32_t>(), what, lo, hi);
    const auto w = r_.word();
    const auto v = to_number<std::int64_t>(w);
    if (!v || *v < lo || *v > hi) {
      r_.fail(fmt::format("{} must be an integer from {} to {}, not {}", what, lo, hi, quoted(w)));
    }
    return *v;
  }
  // A tag written as a size_t: from 1 to `most`.
  std::int64_t tag(std::string_view what, std::int64_t most) {
    if (!binary_) return integer(what, 1, most);
    const auto v = raw<std::uint64_t>();
    if (v < 1 || v > static_cast<std::uint64_t>(most)) {
      r_.fail(fmt::format("{} must be from 1 to {}, not {}", what, most, v));
    }
    return static_cast<std::int64_t>(v);
  }
  // A finite number; a refusal names the node it belongs to, when given.
  double real(std::string_view what, std::optional<std::int64_t> node = std::nullopt) {
    double v = 0;
    std::string text;
    if (binary_) {
      v = raw<double>();
      text = fmt::format("{}", v);
    } else {
      const auto w = r_.word();
      const auto parsed = to_number<double>(w);
      v = parsed.value_or(NAN);
      text = quoted(w);
    }
    if (!std::isfinite(v)) {
      r_.fail(fmt::format("{} must be a finite number, not {}{}", what, text,
                          node ? fmt::format(" (node {})", *node) : std::string()));
    }
    return v;
  }

 private:
  template <class T>
  T raw() {
    T v{};
    std::memcpy(&v, r_.bytes(sizeof(T)).data(), sizeof(T));
    return v;
  }
  std::int64_t in_range(std::int64_t v, std::string_view what, std::int64_t lo, std::int64_t hi) {
    if (v < lo || v > hi) r_.fail(fmt::format("{} must be from {} to {}, not {}", what, lo, hi, v));
    return v;
  }
  Reader& r_;
  bool binary_;
};

// A count from a header, refused when the rest of the file cannot hold that many items of at
// least `bytes_each` bytes: before anything is read or reserved for them.
std::uint64_t claimed(Values& v, std::string_view what, std::size_t bytes_each) {
  const auto n = v.count(what);
  const auto left = v.reader().left();
  if (n > left / bytes_each) {
    v.reader().fail(fmt::format(
        "the header claims {} {}, but the file ends {} bytes later, too soon for them (each "
        "takes at least {} bytes): is it cut short?",
        n, what, left, bytes_each));
  }
  return n;
}

// What the sections read so far declare, for the ones after them.
struct Model {
  bool binary = false;
  bool physical_names = false, entities = false, nodes = false, elements = false;
  std::set<std::pair<std::int64_t, std::int64_t>> entity_tags;  // (dimension, tag)
  std::vector<std::int64_t> node_tags;                          // sorted
};

// The line that closes the section (after its data and any white space).
void expect_end(Reader& r, std::string_view name) {
  const auto end = fmt::format("$End{}", name);
  if (!r.skip_space()) r.ends();
  const auto l = r.line();
  if (l != end) r.fail(fmt::format("the section is not closed by {}: found {}", end, quoted(l)));
}

// The format line: MSH 4.1, ASCII or binary (in this machine's byte order).
bool read_format(Reader& r) {
  r.enter("$MeshFormat", false);
  if (r.left() == 0 || r.line() != "$MeshFormat") {
    r.fail(
        "not a gmsh .msh file (it must start with a line $MeshFormat; snapjump does not read "
        ".geo scripts)");
  }
  const auto format_line = r.line();
  auto rest = format_line;
  const auto version = next_word(rest), type = next_word(rest), size = next_word(rest);
  const auto v = to_number<double>(version);
  if (!v || std::abs(*v - 4.1) > 1e-9) {
    r.fail(fmt::format(
        "MSH version {} is not read: snapjump reads MSH 4.1 (ASCII or binary); `gmsh FILE -save "
        "-format msh41 -o NEW.msh` converts a mesh gmsh can read",
        quoted(version)));
  }
  const auto binary = to_number<int>(type), data_size = to_number<int>(size);
  if (!binary || (*binary != 0 && *binary != 1) || !data_size || (*binary && *data_size != 8)) {
    r.fail(
        fmt::format("the format line must read \"4.1 0 8\" (ASCII) or \"4.1 1 8\" (binary), "
                    "not {}",
                    quoted(format_line)));
  }
  if (*binary) {
    r.enter("$MeshFormat", true);
    Values values(r, true);
    if (values.integer("the byte-order mark", INT_MIN, INT_MAX) != 1) {
      r.fail("the binary data is in another byte order than this machine's (its mark is not 1)");
    }
  }
  expect_end(r, "MeshFormat");
  return *binary == 1;
}

// A name in double quotes, as gmsh reads it (at most 127 characters).
void check_name(Reader& r, std::string_view rest) {
  std::string_view s = rest;
  while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_space(s.back())) s.remove_suffix(1);
  const bool ok = s.size() >= 2 && s.front() == '"' && s.back() == '"' &&
                  s.substr(1, s.size() - 2).find('"') == std::string_view::npos &&
                  s.size() - 2 <= 127;
  if (!ok) r.fail(fmt::format("a physical name must be one quoted name, not {}", quoted(s)));
}

void read_physical_names(Reader& r, Model& m) {
  r.enter("$PhysicalNames", false);
  if (m.physical_names) r.fail("a second $PhysicalNames section");
  m.physical_names = true;
  Values v(r, false);
  // gmsh reads the count from a line of its own.
  auto count_line = r.line();
  const auto count_word = next_word(count_line);
  const auto n = to_number<std::uint64_t>(count_word);
  if (!n || !next_word(count_line).empty()) {
    r.fail(fmt::format("the number of physical names must be a count on a line of its own, not {}",
                       quoted(count_word)));
  }
  if (*n > r.left() / 7) {
    r.fail(fmt::format("the header claims {} physical names, but the file ends {} bytes later", *n,
                       r.left()));
  }
  for (std::uint64_t i = 0; i < *n; ++i) {
    (void)v.integer("a physical name's dimension", 0, 3);
    (void)v.integer("a physical tag", -INT_MAX, INT_MAX);
    check_name(r, r.line(kMaxNameLine));
  }
  expect_end(r, "PhysicalNames");
}

// One entity of $Entities: tag, bounding box, physical tags, bounding entities.
void read_entity(Values& v, int dim, Model& m) {
  const auto tag = v.integer("an entity tag", 0, INT_MAX);
  if (!m.entity_tags.emplace(dim, tag).second) {
    v.reader().fail(fmt::format("entity {} of dimension {} is declared twice", tag, dim));
  }
  for (int k = 0; k < (dim == 0 ? 3 : 6); ++k) (void)v.real("a bounding-box coordinate");
  const std::size_t int_bytes = v.binary() ? 4 : 2;
  const auto physicals = claimed(v, "physical tags", int_bytes);
  for (std::uint64_t k = 0; k < physicals; ++k)
    (void)v.integer("a physical tag", -INT_MAX, INT_MAX);
  if (dim == 0) return;
  const auto bounds = claimed(v, "bounding entities", int_bytes);
  for (std::uint64_t k = 0; k < bounds; ++k) {
    (void)v.integer("a bounding entity's tag", -INT_MAX, INT_MAX);
  }
}

void read_entities(Reader& r, Model& m) {
  r.enter("$Entities", m.binary);
  if (m.entities || m.nodes) r.fail("$Entities must come once, before $Nodes");
  m.entities = true;
  Values v(r, m.binary);
  constexpr const char* kinds[4] = {"points", "curves", "surfaces", "volumes"};
  std::array<std::uint64_t, 4> n{};
  for (int d = 0; d < 4; ++d) n[d] = claimed(v, kinds[d], m.binary ? 36 : 10);
  for (int d = 0; d < 4; ++d) {
    for (std::uint64_t i = 0; i < n[d]; ++i) read_entity(v, d, m);
  }
  expect_end(r, "Entities");
}

using TagAt = std::pair<std::int64_t, std::size_t>;  // a node tag and where the file has it

void read_node_block(Values& v, std::uint64_t room, std::vector<TagAt>& tags) {
  const auto dim = v.integer("a node block's entity dimension", 0, 3);
  (void)v.integer("a node block's entity tag", 0, INT_MAX);
  const auto parametric = v.integer("a node block's parametric flag", 0, 1);
  const auto n = claimed(v, "nodes in the block", v.binary() ? 32 : 8);
  if (n > room) {
    v.reader().fail(
        fmt::format("the block holds {} nodes, more than the {} left of the header's "
                    "count",
                    n, room));
  }
  const auto first = tags.size();
  for (std::uint64_t i = 0; i < n; ++i) {
    const auto tag = v.tag("a node tag", kMaxNodeTag);
    tags.emplace_back(tag, v.reader().mark());
  }
  // The block's tags come first, then each node's coordinates in the same order.
  const auto per_node = static_cast<std::uint64_t>(3 + (parametric ? dim : 0));
  for (std::uint64_t i = 0; i < n; ++i) {
    for (std::uint64_t k = 0; k < per_node; ++k)
      (void)v.real("a node coordinate", tags[first + i].first);
  }
}

// The node tags, sorted; a tag given twice is refused where it comes the second time.
std::vector<std::int64_t> unique_tags(Reader& r, std::vector<TagAt>& tags) {
  std::sort(tags.begin(), tags.end());
  std::vector<std::int64_t> out;
  out.reserve(tags.size());
  for (std::size_t k = 0; k < tags.size(); ++k) {
    if (k > 0 && tags[k].first == tags[k - 1].first) {
      r.fail_at(tags[k].second, fmt::format("node tag {} appears twice", tags[k].first));
    }
    out.push_back(tags[k].first);
  }
  return out;
}

void read_nodes(Reader& r, Model& m) {
  r.enter("$Nodes", m.binary);
  if (!m.entities || m.nodes) r.fail("$Nodes must come once, after $Entities");
  m.nodes = true;
  Values v(r, m.binary);
  const auto blocks = claimed(v, "node blocks", m.binary ? 20 : 8);
  const auto total = claimed(v, "nodes", m.binary ? 32 : 8);
  (void)v.count("the smallest node tag");
  (void)v.count("the largest node tag");
  std::vector<TagAt> tags;
  tags.reserve(total);
  for (std::uint64_t b = 0; b < blocks; ++b) read_node_block(v, total - tags.size(), tags);
  if (tags.size() != total) {
    r.fail(fmt::format("the blocks hold {} nodes, the header says {}", tags.size(), total));
  }
  expect_end(r, "Nodes");
  m.node_tags = unique_tags(r, tags);
}

void check_node(Reader& r, const Model& m, std::int64_t element, std::int64_t node,
                std::size_t pos) {
  if (!std::binary_search(m.node_tags.begin(), m.node_tags.end(), node)) {
    r.fail_at(pos, fmt::format("element {} refers to node {}, which $Nodes does not hold", element,
                               node));
  }
}

// One element: its tag and node tags (in ASCII, on the rest of its tag's line, as gmsh reads).
void read_element(Values& v, const Model& m, int nodes) {
  Reader& r = v.reader();
  const auto element = v.tag("an element tag", kMaxTag);
  if (v.binary()) {
    for (int a = 0; a < nodes; ++a) {
      const auto node = v.tag("a node tag", kMaxTag);
      check_node(r, m, element, node, r.mark());
    }
    return;
  }
  auto rest = r.line(kMaxElementLine);
  if (r.left() == 0) r.ends();  // the last line of a cut file, or one without $EndElements
  for (int a = 0; a < nodes; ++a) {
    const auto w = next_word(rest);
    if (w.empty()) {
      r.fail(fmt::format("element {} has {} node tags; its type has {}", element, a, nodes));
    }
    const auto node = to_number<std::int64_t>(w);
    if (!node || *node < 1) {
      r.fail_at(r.pos_of(w),
                fmt::format("a node tag must be a positive integer, not {}", quoted(w)));
    }
    check_node(r, m, element, *node, r.pos_of(w));
  }
  if (!next_word(rest).empty()) {
    r.fail(fmt::format("element {} has more node tags than its type's {}", element, nodes));
  }
}

std::uint64_t read_element_block(Values& v, const Model& m, std::uint64_t room) {
  Reader& r = v.reader();
  const auto dim = v.integer("an element block's entity dimension", 0, 3);
  const auto entity = v.integer("an element block's entity tag", 0, INT_MAX);
  if (m.entity_tags.count({dim, entity}) == 0) {
    r.fail(fmt::format("elements on entity {} of dimension {}, which $Entities does not declare",
                       entity, dim));
  }
  const auto type_tag = v.integer("an element type", INT_MIN, INT_MAX);
  const auto type = msh_element_type(type_tag);
  if (!type) r.fail(fmt::format("element type {} is not one of gmsh's types 1 to 31", type_tag));
  if (type->dim != dim) {
    r.fail(fmt::format("element type {} has dimension {}, its block's entity {}", type_tag,
                       type->dim, dim));
  }
  const auto each = static_cast<std::size_t>(1 + type->nodes) * (v.binary() ? 8 : 2);
  const auto n = claimed(v, "elements in the block", each);
  if (n > room) {
    r.fail(fmt::format("the block holds {} elements, more than the {} left of the header's count",
                       n, room));
  }
  for (std::uint64_t i = 0; i < n; ++i) read_element(v, m, type->nodes);
  return n;
}

void read_elements(Reader& r, Model& m) {
  r.enter("$Elements", m.binary);
  if (!m.nodes || m.elements) r.fail("$Elements must come once, after $Nodes");
  m.elements = true;
  Values v(r, m.binary);
  const auto blocks = claimed(v, "element blocks", m.binary ? 20 : 8);
  const auto total = claimed(v, "elements", m.binary ? 16 : 4);
  (void)v.count("the smallest element tag");
  (void)v.count("the largest element tag");
  std::uint64_t seen = 0;
  for (std::uint64_t b = 0; b < blocks; ++b) seen += read_element_block(v, m, total - seen);
  if (seen != total) {
    r.fail(fmt::format("the blocks hold {} elements, the header says {}", seen, total));
  }
  expect_end(r, "Elements");
}

// The sections gmsh reads, which it finds by the beginning of their names; snapjump does not
// use those after the first five (periodic, partitioned or post-processing data).
constexpr std::array<std::string_view, 12> kGmshSections = {"MeshFormat",
                                                            "PhysicalNames",
                                                            "Entities",
                                                            "Nodes",
                                                            "Elements",
                                                            "Periodic",
                                                            "PartitionedEntities",
                                                            "GhostElements",
                                                            "Parametrizations",
                                                            "NodeData",
                                                            "ElementData",
                                                            "ElementNodeData"};

// Refuses a section that gmsh would read but the check does not.
void refuse_gmsh_section(Reader& r, const std::string& name) {
  if (name == "MeshFormat") r.fail("a second $MeshFormat section");
  for (const auto known : kGmshSections) {
    if (name == known) {
      r.fail(
          fmt::format("the ${} section holds data snapjump does not read (periodic, "
                      "partitioned or post-processing data): save the mesh without it",
                      name));
    }
    if (name.starts_with(known)) {
      r.fail(fmt::format("gmsh reads a section named ${} as ${}: name it exactly", name, known));
    }
  }
  if (name.starts_with("End")) r.fail(fmt::format("${} closes no section", name));
}

// A section gmsh does not know: it keeps its lines as they are, up to the section's $End line.
void skip_section(Reader& r, const std::string& name) {
  refuse_gmsh_section(r, name);
  r.enter("$" + name, false);
  const auto end = "$End" + name;
  while (r.line() != end) {
  }
}

void read_section(Reader& r, const std::string& name, Model& m) {
  if (name == "PhysicalNames") return read_physical_names(r, m);
  if (name == "Entities") return read_entities(r, m);
  if (name == "Nodes") return read_nodes(r, m);
  if (name == "Elements") return read_elements(r, m);
  skip_section(r, name);
}

bool is_section_name(std::string_view s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](unsigned char c) {
    return std::isalnum(c) != 0 || c == '_';
  });
}

}  // namespace

void check_msh_bytes(std::string_view bytes, const std::string& name) {
  Reader r(bytes, name);
  Model m;
  m.binary = read_format(r);
  while (r.skip_space()) {
    r.enter("", false);
    const auto header = r.line();
    if (header.empty() || header.front() != '$' || !is_section_name(header.substr(1))) {
      r.fail(fmt::format("expected a section header ($Name), not {}", quoted(header)));
    }
    read_section(r, std::string(header.substr(1)), m);
  }
  r.enter("", false);
  if (!m.elements) r.fail_at(bytes.size(), "the file has no $Entities, $Nodes and $Elements");
}

void check_msh_file(const std::filesystem::path& path) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  std::ifstream in(path, std::ios::binary);
  if (ec || !in) throw MeshError(fmt::format("{}: cannot be read", path.string()));
  std::string bytes(static_cast<std::size_t>(size), '\0');
  in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (in.gcount() != static_cast<std::streamsize>(bytes.size())) {
    throw MeshError(
        fmt::format("{}: cannot be read (it changed while it was read)", path.string()));
  }
  check_msh_bytes(bytes, path.string());
}

std::optional<MshElementType> msh_element_type(std::int64_t type) {
  if (type < 1 || type > static_cast<std::int64_t>(kTypes.size())) return std::nullopt;
  return kTypes[static_cast<std::size_t>(type - 1)];
}

}  // namespace snapjump::mesh
