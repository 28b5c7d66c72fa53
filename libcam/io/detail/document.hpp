#pragma once
// A structured camera file (YAML, OpenCV's XML, JSON) as one small tree, so that every
// reader of such a file (OpenCV's FileStorage layouts, and the calibration files of
// other tools) works on the same thing and reports errors the same way: the file, the
// line where the format records one, the field and the value.
//
// The parsers behind it are yaml-cpp (the YAML parser ROS and Kalibr read their
// files with), pugixml and nlohmann JSON; none appears in this header.

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace libcam {

// One node of a parsed file. Scalars keep their text as written (unquoted); numbers
// are read from it by Field below, with libcam's own checks.
struct DocumentNode {
    enum class Kind { Null, Scalar, Sequence, Map };
    Kind kind = Kind::Null;
    std::string text;                // Scalar: its text
    // "opencv-matrix" for YAML's !!opencv-matrix or XML's type_id="opencv-matrix"; JSON's
    // type of a value: "string", "number", "boolean", "null" (a string that reads as a
    // number is still a string).
    std::string tag;
    std::vector<DocumentNode> items;  // Sequence: its items; Map: the values of `keys`
    std::vector<std::string> keys;    // Map: its keys, in file order, each once
    int line = 0;                    // where the node starts, counted from 1 (0: not known)

    // The value of `key` in a map, or null when this is not a map or has no such key.
    const DocumentNode* find(std::string_view key) const;
};

// The most a file may nest (a camera file nests three or four levels). Deeper files are
// refused before anything recurses through them.
constexpr int kMaxDocumentDepth = 32;

// Parses YAML (one document). OpenCV's own header line "%YAML:1.0", which YAML
// parsers refuse, is accepted, with or without the "---" after it; CRLF line ends are
// accepted. A file whose last key has no value is refused as cut short. Throws
// FileError "<source>: line L: <what the parser says>".
DocumentNode parse_yaml_document(std::string_view text, const std::string& source);

// Parses XML as OpenCV's FileStorage lays it out: the root element's children are the
// top-level keys; an element with child elements is a map (a sequence when its children
// are all "_"); an element with text is a scalar, or a sequence of scalars when its text
// holds several whitespace-separated words; the attribute type_id becomes the tag.
DocumentNode parse_opencv_xml_document(std::string_view text, const std::string& source);

// The outline of any XML file, for telling formats apart by their elements: a map whose
// one key is the root element's name, holding a map of its child elements' names (each
// once, with no value). Throws FileError "<source>: line L: not valid XML: ...".
DocumentNode parse_xml_outline(std::string_view text, const std::string& source);

// Parses JSON into the same tree: objects are maps (keys in file order), arrays
// sequences, strings, numbers and booleans scalars with their text as written (a string
// without its quotes), null null; each tagged with its JSON type. A key given twice keeps
// its first place and its last value, as JSON libraries read it. JSON records no lines
// (every node's is 0). Throws FileError "<source>: \"<key.path>\": not valid JSON: ..."
// (the key where parsing stopped), "... must be finite, got 1e999" for a number past a
// double's range, or for a file nested deeper than kMaxDocumentDepth.
DocumentNode parse_json_tree(std::string_view text, const std::string& source);

// File detection parses a file to see whose keys it holds, and the reader it picks then
// parses the same text again: kept here, detection's tree is taken by the next
// parse_json_tree or parse_yaml_document of that very text and source instead of a second
// parse (yaml-cpp reads a few MB/s). One tree is kept per thread, until the next parse.
enum class DocumentSyntax { Json, Yaml };
void keep_parsed_document(DocumentSyntax syntax, std::string_view text, const std::string& source, DocumentNode tree);

// A double as YAML that every YAML reader takes as a float, Python's (PyYAML, which Kalibr
// and ROS's Python tools read with) included: every digit that matters, with a '.' in
// the mantissa ("1.0e-09", "500.0", not "1e-09" or "500", which PyYAML reads as a string
// and an integer).
std::string yaml_number(double value);

// A node with the name a user knows it by ("camera_matrix.data", "frames[2].fl_x") and
// the file it came from, for reading values with messages that say where a bad value is:
// "<source>: line 7: \"camera_matrix.data\"[3]: must be finite, got .inf" (no line for
// JSON, which records none).
class Field {
public:
    Field(const DocumentNode& node, std::string name, const std::string& source);

    const DocumentNode& node() const { return *node_; }
    const std::string& name() const { return name_; }
    const std::string& source() const { return *source_; }

    // A key of this map: the first of `keys` present (later names are older
    // spellings), or nothing. Fails unless this is a map, and when the key is there
    // with no value (YAML's `key:` and nothing after it): a field left empty is not
    // guessed at. JSON's null counts as absent: JSON writers write it for a value they
    // do not have.
    std::optional<Field> find(std::initializer_list<std::string_view> keys) const;
    // The same, failing with "missing" (naming the first key) when none is present.
    Field at(std::initializer_list<std::string_view> keys) const;
    // A sequence's length; fails unless this is a sequence.
    std::size_t size() const;
    // Item `index` of a sequence, named "<name>[index]"; fails unless there is one.
    Field item(std::size_t index) const;

    std::string text() const;                             // a scalar's text, not a JSON number or boolean
    double number() const;                                // a finite number, not a JSON string ("500")
    long long integer(long long min, long long max) const;  // a decimal integer in [min, max]
    // A number with no fraction in [min, max] (instant-ngp writes sizes as 1080.0).
    long long whole_number(long long min, long long max) const;
    // A sequence of finite numbers (a single scalar counts as one), at most max_count.
    std::vector<double> numbers(std::size_t max_count) const;
    // true or false when this is a boolean (JSON's true and false), nothing otherwise.
    std::optional<bool> boolean() const;
    // The value as a message shows it: a word in '' (a JSON string in ""), "a list of 3",
    // "keys and values", "null".
    std::string shown() const;

    // Throws FileError naming the source, line and field: "<source>: line L: \"<name>\": <what>"
    // ("<source>: \"<name>\": <what>" where the line is not known).
    [[noreturn]] void fail(const std::string& what) const;
    // The same for a key of this map, whether or not it is there ("missing", or a value
    // that disagrees with another key): "<source>: \"<name>.<key>\": <what>".
    [[noreturn]] void fail_at(std::string_view key, const std::string& what) const;

private:
    Field(const DocumentNode& node, std::string name, const std::string* source);
    double number_at(const DocumentNode& scalar, std::size_t index, bool indexed) const;
    std::string child_name(std::string_view key) const;  // "camera_matrix.data"

    const DocumentNode* node_;
    std::string name_;
    const std::string* source_;
};

}  // namespace libcam
