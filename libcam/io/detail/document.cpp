#include "libcam/io/detail/document.hpp"

#include <yaml-cpp/anchor.h>
#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/exceptions.h>
#include <yaml-cpp/mark.h>
#include <yaml-cpp/parser.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>
#include <optional>
#include <sstream>
#include <nlohmann/json.hpp>
#include <pugixml.hpp>
#include <system_error>
#include <unordered_map>

#include "libcam/error.hpp"
#include "libcam/text/number_format.hpp"
#include "libcam/text/shown_value.hpp"

namespace libcam {

const DocumentNode* DocumentNode::find(std::string_view key) const {
    if (kind != Kind::Map) return nullptr;
    for (std::size_t i = 0; i < keys.size(); ++i) {
        if (keys[i] == key) return &items[i];
    }
    return nullptr;
}

namespace {

// The most nodes a file may hold. A camera file holds a few dozen; the cap stops a
// small YAML file whose aliases refer to each other ("billion laughs") from growing
// into an exponentially large tree.
constexpr std::size_t kMaxDocumentNodes = 200000;

// Counts the nodes built and the depth reached, refusing a file past either limit.
class TreeBudget {
public:
    explicit TreeBudget(const std::string& source) : source_(source) {}

    void enter(int depth, int line) {
        if (depth > kMaxDocumentDepth) refuse(line, "nested more than " + std::to_string(kMaxDocumentDepth) + " levels deep");
        if (++nodes_ > kMaxDocumentNodes) refuse(line, "more than " + std::to_string(kMaxDocumentNodes) + " values");
    }
    // An alias: `count` more nodes at once.
    void add(std::size_t count, int line) {
        nodes_ += count;
        if (nodes_ > kMaxDocumentNodes) refuse(line, "more than " + std::to_string(kMaxDocumentNodes) + " values");
    }
    [[noreturn]] void refuse(int line, const std::string& what) const {
        throw FileError(source_ + (line > 0 ? ": line " + std::to_string(line) : "") + ": " + what);
    }

private:
    const std::string& source_;
    std::size_t nodes_ = 0;
};

// ---- the tree detection parsed, for the reader (keep_parsed_document) ----

struct KeptDocument {
    DocumentSyntax syntax;
    std::string text;  // compared whole: a buffer freed and reused at the same address is another file
    std::string source;
    DocumentNode tree;
};

thread_local std::optional<KeptDocument> kept_document;

// The kept tree when it is this text's, parsed the same way; the slot is emptied either way,
// so that a tree no reader takes is not held on to.
std::optional<DocumentNode> take_kept_document(DocumentSyntax syntax, std::string_view text,
                                               const std::string& source) {
    if (!kept_document) return std::nullopt;
    KeptDocument kept = std::move(*kept_document);
    kept_document.reset();
    if (kept.syntax != syntax || kept.source != source || kept.text != text) return std::nullopt;
    return std::move(kept.tree);
}

// ---- YAML (yaml-cpp) ----

std::string yaml_tag(const std::string& tag) {
    constexpr std::string_view kCore = "tag:yaml.org,2002:";  // what "!!" stands for
    if (tag == "?" || tag == "!") return "";                  // untagged (plain or quoted)
    if (std::string_view(tag).starts_with(kCore)) return tag.substr(kCore.size());
    return tag;
}

std::size_t count_nodes(const DocumentNode& node) {
    std::size_t count = 1;
    for (const DocumentNode& item : node.items) count += count_nodes(item);
    return count;
}

int depth_below(const DocumentNode& node) {
    int depth = 0;
    for (const DocumentNode& item : node.items) depth = std::max(depth, 1 + depth_below(item));
    return depth;
}

// Builds the tree straight from yaml-cpp's parse events (one document), so that no
// other tree is built first and the budget is counted as it grows. An alias is a copy
// of the node its anchor named, counted again.
class TreeBuilder : public YAML::EventHandler {
public:
    TreeBuilder(TreeBudget& budget, std::string_view text) : budget_(budget), text_(text) {}

    DocumentNode take() { return std::move(root_); }

    void OnDocumentStart(const YAML::Mark&) override {}
    void OnDocumentEnd() override {}
    void OnNull(const YAML::Mark& mark, YAML::anchor_t anchor) override { add(leaf(mark, DocumentNode::Kind::Null, "", ""), anchor); }
    void OnAlias(const YAML::Mark& mark, YAML::anchor_t anchor) override {
        const auto found = anchors_.find(anchor);
        if (found == anchors_.end()) budget_.refuse(line_of(mark), "an alias to an unknown anchor");
        budget_.enter(static_cast<int>(open_.size()) + depth_below(found->second), line_of(mark));
        budget_.add(count_nodes(found->second), line_of(mark));
        add(DocumentNode(found->second), YAML::NullAnchor);
    }
    void OnScalar(const YAML::Mark& mark, const std::string& tag, YAML::anchor_t anchor, const std::string& value) override {
        if (tag == "!") check_quote_closed(mark);
        add(leaf(mark, DocumentNode::Kind::Scalar, tag, value), anchor);
    }
    void OnSequenceStart(const YAML::Mark& mark, const std::string& tag, YAML::anchor_t anchor,
                         YAML::EmitterStyle::value) override {
        open(mark, DocumentNode::Kind::Sequence, tag, anchor);
    }
    void OnSequenceEnd() override { close(); }
    void OnMapStart(const YAML::Mark& mark, const std::string& tag, YAML::anchor_t anchor, YAML::EmitterStyle::value) override {
        open(mark, DocumentNode::Kind::Map, tag, anchor);
    }
    void OnMapEnd() override { close(); }

private:
    struct Open {
        DocumentNode node;
        YAML::anchor_t anchor;
        std::optional<std::string> key;  // a map's key waiting for its value
        std::unordered_map<std::string, int> keys_seen;  // a map's keys so far, with their lines
    };

    static int line_of(const YAML::Mark& mark) { return mark.is_null() ? 0 : mark.line + 1; }

    // yaml-cpp reads a quoted value whose closing quote never comes as running to the
    // end of the file, so `name: "left` as a file's last line reads as "left ". A YAML
    // parser must refuse that; this one is told to.
    void check_quote_closed(const YAML::Mark& mark) const {
        if (mark.is_null() || mark.pos < 0 || static_cast<std::size_t>(mark.pos) >= text_.size()) return;
        const char quote = text_[static_cast<std::size_t>(mark.pos)];
        if (quote != '"' && quote != '\'') return;  // a tag or block scalar, not a quote
        for (std::size_t i = static_cast<std::size_t>(mark.pos) + 1; i < text_.size(); ++i) {
            if (quote == '"' && text_[i] == '\\') {
                ++i;  // an escaped character, \" among them
            } else if (text_[i] == quote) {
                if (quote == '\'' && i + 1 < text_.size() && text_[i + 1] == '\'') {
                    ++i;  // '' is a quote inside single quotes
                } else {
                    return;
                }
            }
        }
        budget_.refuse(line_of(mark), std::string("a value opened with ") + quote + " and never closed");
    }

    DocumentNode leaf(const YAML::Mark& mark, DocumentNode::Kind kind, const std::string& tag, const std::string& text) {
        budget_.enter(static_cast<int>(open_.size()), line_of(mark));
        DocumentNode node;
        node.kind = kind;
        node.tag = yaml_tag(tag);
        node.text = text;
        node.line = line_of(mark);
        return node;
    }

    void open(const YAML::Mark& mark, DocumentNode::Kind kind, const std::string& tag, YAML::anchor_t anchor) {
        if (!open_.empty() && open_.back().node.kind == DocumentNode::Kind::Map && !open_.back().key) {
            budget_.refuse(line_of(mark), "a key that is not text");
        }
        open_.push_back({leaf(mark, kind, tag, ""), anchor, std::nullopt, {}});
    }

    void close() {
        Open done = std::move(open_.back());
        open_.pop_back();
        if (done.key) budget_.refuse(done.node.line, "the key \"" + *done.key + "\" has no value");
        add(std::move(done.node), done.anchor);
    }

    // Puts a finished node where it belongs: the root, a sequence's next item, a map's
    // next key, or the value of the key before it.
    void add(DocumentNode node, YAML::anchor_t anchor) {
        if (anchor != YAML::NullAnchor) anchors_[anchor] = node;
        if (open_.empty()) {
            root_ = std::move(node);
            return;
        }
        Open& parent = open_.back();
        if (parent.node.kind == DocumentNode::Kind::Sequence) {
            parent.node.items.push_back(std::move(node));
        } else if (!parent.key) {
            if (node.kind != DocumentNode::Kind::Scalar && node.kind != DocumentNode::Kind::Null) {
                budget_.refuse(node.line, "a key that is not text");
            }
            // yaml-cpp takes a repeated key without a word; which value a reader then
            // sees depends on the reader, so the file is refused.
            const auto [first, is_new] = parent.keys_seen.emplace(node.text, node.line);
            if (!is_new) {
                budget_.refuse(node.line, "the key " + shown_value(node.text, '"') + " appears twice (first on line " +
                                              std::to_string(first->second) + ")");
            }
            parent.key = std::move(node.text);
        } else {
            parent.node.keys.push_back(std::move(*parent.key));
            parent.node.items.push_back(std::move(node));
            parent.key.reset();
        }
    }

    TreeBudget& budget_;
    std::string_view text_;  // what the parser reads, for the quote check
    std::vector<Open> open_;
    std::map<YAML::anchor_t, DocumentNode> anchors_;
    DocumentNode root_;
};

// Counts the events of a document without keeping them: only whether there is one.
class NothingBuilder : public YAML::EventHandler {
public:
    void OnDocumentStart(const YAML::Mark&) override {}
    void OnDocumentEnd() override {}
    void OnNull(const YAML::Mark&, YAML::anchor_t) override {}
    void OnAlias(const YAML::Mark&, YAML::anchor_t) override {}
    void OnScalar(const YAML::Mark&, const std::string&, YAML::anchor_t, const std::string&) override {}
    void OnSequenceStart(const YAML::Mark&, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {}
    void OnSequenceEnd() override {}
    void OnMapStart(const YAML::Mark&, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {}
    void OnMapEnd() override {}
};

// OpenCV begins its YAML with "%YAML:1.0", which is not a YAML directive (YAML's is
// "%YAML 1.2"), and writes "---" after it only sometimes (ORB-SLAM's settings have
// none). The header line is blanked, whichever form it has, so the line numbers of the
// rest stay those of the file.
std::string without_yaml_header(std::string_view text) {
    std::string out(text);
    std::size_t start = 0;
    if (std::string_view(out).starts_with("\xEF\xBB\xBF")) start = 3;  // a UTF-8 byte-order mark
    if (std::string_view(out).substr(start).starts_with("%YAML")) {
        const std::size_t end = std::min(out.find('\n', start), out.size());
        std::fill(out.begin() + static_cast<std::ptrdiff_t>(start), out.begin() + static_cast<std::ptrdiff_t>(end), ' ');
    }
    return out;
}

// A camera file is one YAML document. A line that starts with "---" after the
// document's content has begun starts another one, and so does content after a "..."
// line (in YAML such lines end a document wherever they stand, even inside brackets).
void check_one_yaml_document(std::string_view text, const std::string& source) {
    bool content = false, ended = false;
    int line_number = 0;
    for (std::size_t start = 0; start < text.size();) {
        const std::size_t end = std::min(text.find('\n', start), text.size());
        const std::string_view line = text.substr(start, end - start);
        start = end + 1;
        ++line_number;
        const auto second_document = [&] {
            throw FileError(source + ": line " + std::to_string(line_number) +
                            ": a second YAML document (a camera file holds one)");
        };
        const bool marker = (line.starts_with("---") || line.starts_with("...")) &&
                            (line.size() == 3 || line[3] == ' ' || line[3] == '\t' || line[3] == '\r');
        const std::size_t first = line.find_first_not_of(" \t\r", marker ? 3 : 0);
        const bool holds_content = first != std::string_view::npos && line[first] != '#' && (marker || line[first] != '%');
        if (marker && line.starts_with("...")) {
            ended = ended || content;
            continue;
        }
        if ((marker && content) || (holds_content && ended)) second_document();
        content = content || holds_content;
    }
}

// ---- OpenCV's XML (pugixml) ----

class LineIndex {
public:
    explicit LineIndex(std::string_view text) {
        for (std::size_t i = 0; i < text.size(); ++i) {
            if (text[i] == '\n') ends_.push_back(i);
        }
    }
    int line_of(std::ptrdiff_t offset) const {
        if (offset < 0) return 0;
        return static_cast<int>(std::lower_bound(ends_.begin(), ends_.end(), static_cast<std::size_t>(offset)) -
                                ends_.begin()) + 1;
    }

private:
    std::vector<std::size_t> ends_;
};

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }

std::string_view trim(std::string_view text) {
    while (!text.empty() && is_space(text.front())) text.remove_prefix(1);
    while (!text.empty() && is_space(text.back())) text.remove_suffix(1);
    return text;
}

std::vector<std::string> words_of(std::string_view text) {
    std::vector<std::string> words;
    std::size_t i = 0;
    while (i < text.size()) {
        while (i < text.size() && is_space(text[i])) ++i;
        const std::size_t start = i;
        while (i < text.size() && !is_space(text[i])) ++i;
        if (i > start) words.emplace_back(text.substr(start, i - start));
    }
    return words;
}

DocumentNode from_xml(const pugi::xml_node& element, int depth, TreeBudget& budget, const LineIndex& lines) {
    DocumentNode out;
    out.line = lines.line_of(element.offset_debug());
    budget.enter(depth, out.line);
    out.tag = element.attribute("type_id").value();
    std::vector<pugi::xml_node> children;
    for (const pugi::xml_node& child : element.children()) {
        if (child.type() == pugi::node_element) children.push_back(child);
    }
    if (!children.empty()) {
        const bool sequence =
            std::all_of(children.begin(), children.end(), [](const pugi::xml_node& c) { return std::string_view(c.name()) == "_"; });
        out.kind = sequence ? DocumentNode::Kind::Sequence : DocumentNode::Kind::Map;
        std::unordered_map<std::string, int> keys_seen;  // with their lines
        for (const pugi::xml_node& child : children) {
            if (!sequence) {
                const std::string key = child.name();
                const int line = lines.line_of(child.offset_debug());
                const auto [first, is_new] = keys_seen.emplace(key, line);
                if (!is_new) {
                    budget.refuse(line, "the element <" + printable_text(key, kShownValueLength) + "> appears twice (first on line " +
                                            std::to_string(first->second) + ")");
                }
                out.keys.push_back(key);
            }
            out.items.push_back(from_xml(child, depth + 1, budget, lines));
        }
        return out;
    }
    std::string text;
    for (const pugi::xml_node& child : element.children()) {
        if (child.type() == pugi::node_pcdata || child.type() == pugi::node_cdata) text += child.value();
    }
    const std::string_view trimmed = trim(text);
    if (trimmed.size() >= 2 && trimmed.front() == '"' && trimmed.back() == '"') {  // a string OpenCV quoted
        out.kind = DocumentNode::Kind::Scalar;
        out.text = std::string(trimmed.substr(1, trimmed.size() - 2));
        return out;
    }
    std::vector<std::string> words = words_of(trimmed);
    if (words.size() == 1) {
        out.kind = DocumentNode::Kind::Scalar;
        out.text = std::move(words.front());
    } else if (words.size() > 1) {
        out.kind = DocumentNode::Kind::Sequence;
        out.items.reserve(words.size());
        for (std::string& word : words) {
            budget.enter(depth + 1, out.line);
            DocumentNode item;
            item.kind = DocumentNode::Kind::Scalar;
            item.text = std::move(word);
            item.line = out.line;
            out.items.push_back(std::move(item));
        }
    }
    return out;
}

}  // namespace

std::string yaml_number(double value) {
    std::string text = format_number(value + 0.0);
    if (text.find_first_of("ni") != std::string::npos) return text;  // nan, inf: not camera values
    const auto exponent = text.find('e');
    if (text.find('.') == std::string::npos) text.insert(exponent == std::string::npos ? text.size() : exponent, ".0");
    return text;
}

void keep_parsed_document(DocumentSyntax syntax, std::string_view text, const std::string& source, DocumentNode tree) {
    kept_document = KeptDocument{syntax, std::string(text), source, std::move(tree)};
}

DocumentNode parse_yaml_document(std::string_view text, const std::string& source) {
    std::optional<DocumentNode> kept = take_kept_document(DocumentSyntax::Yaml, text, source);
    if (kept) return std::move(*kept);
    const std::string yaml = without_yaml_header(text);
    check_one_yaml_document(yaml, source);
    TreeBudget budget(source);
    DocumentNode tree;
    try {
        std::istringstream stream(yaml);
        YAML::Parser parser(stream);
        TreeBuilder builder(budget, yaml);
        if (parser.HandleNextDocument(builder)) tree = builder.take();
        // Whatever the parser did not take as the first document must be nothing. (One
        // more call, never a loop: yaml-cpp 0.7's LoadAll loops forever on some malformed
        // files, a document that starts with ',' among them; found by fuzzing.)
        NothingBuilder rest;
        if (parser.HandleNextDocument(rest)) throw FileError(source + ": text after the YAML document (not valid YAML)");
    } catch (const YAML::Exception& error) {
        const std::string where = error.mark.is_null() ? "" : ": line " + std::to_string(error.mark.line + 1);
        throw FileError(source + where + ": not valid YAML: " + error.msg);
    } catch (const Error&) {
        throw;
    } catch (const std::exception& error) {
        throw FileError(source + ": not valid YAML: " + error.what());
    }
    // YAML has no closing bracket to show that a file is whole; a file cut short within
    // its last key ("distortion_coeffici") reads as that key with no value. Refused, so
    // that a cut file never reads as a camera without its last field.
    if (tree.kind == DocumentNode::Kind::Map && !tree.items.empty() && tree.items.back().kind == DocumentNode::Kind::Null) {
        const int line = tree.items.back().line;
        throw FileError(source + (line > 0 ? ": line " + std::to_string(line) : "") + ": the file ends with the key " +
                        shown_value(tree.keys.back(), '"') +
                        " and no value (is it cut short?)");
    }
    return tree;
}

DocumentNode parse_opencv_xml_document(std::string_view text, const std::string& source) {
    pugi::xml_document document;
    const pugi::xml_parse_result result = document.load_buffer(text.data(), text.size());
    const LineIndex lines(text);
    if (!result) {
        throw FileError(source + ": line " + std::to_string(lines.line_of(result.offset)) +
                        ": not valid XML: " + result.description());
    }
    const pugi::xml_node root = document.document_element();
    if (std::string_view(root.name()) != "opencv_storage") {
        throw FileError(source + ": expected the root element <opencv_storage> of OpenCV's XML, got <" +
                        printable_text(root.name(), kShownValueLength) + ">");
    }
    TreeBudget budget(source);
    DocumentNode tree = from_xml(root, 0, budget, lines);
    if (tree.kind == DocumentNode::Kind::Null) tree.kind = DocumentNode::Kind::Map;  // <opencv_storage/>: no keys
    if (tree.kind != DocumentNode::Kind::Map) throw FileError(source + ": <opencv_storage> holds no keys");
    return tree;
}

DocumentNode parse_xml_outline(std::string_view text, const std::string& source) {
    pugi::xml_document document;
    const pugi::xml_parse_result result = document.load_buffer(text.data(), text.size());
    if (!result) {
        throw FileError(source + ": line " + std::to_string(LineIndex(text).line_of(result.offset)) +
                        ": not valid XML: " + result.description());
    }
    const pugi::xml_node root = document.document_element();
    DocumentNode children;
    children.kind = DocumentNode::Kind::Map;
    for (const pugi::xml_node child : root.children()) {
        if (child.type() != pugi::node_element || children.find(child.name()) != nullptr) continue;
        children.keys.emplace_back(child.name());
        children.items.emplace_back();
    }
    DocumentNode outline;
    outline.kind = DocumentNode::Kind::Map;
    outline.keys.emplace_back(root.name());
    outline.items.push_back(std::move(children));
    return outline;
}

// ---- JSON (nlohmann) ----

namespace {

// Builds the tree straight from nlohmann's parse events, so that no other tree is built
// first, the depth is checked before anything nests deeper, and a parse error can name
// the key it stopped in.
class JsonTreeBuilder : public nlohmann::json_sax<nlohmann::json> {
public:
    explicit JsonTreeBuilder(const std::string& source) : source_(source) {}

    DocumentNode take() { return std::move(root_); }
    // Why the parse stopped, with the key it stopped in: "<source>: \"K[2]\": ...".
    [[noreturn]] void refuse() const { throw FileError(source_ + where() + ": " + error_); }

    bool null() override { return add(scalar(DocumentNode::Kind::Null, "", "null")); }
    bool boolean(bool value) override { return add(scalar(DocumentNode::Kind::Scalar, value ? "true" : "false", "boolean")); }
    bool number_integer(number_integer_t value) override { return number(std::to_string(value)); }
    bool number_unsigned(number_unsigned_t value) override { return number(std::to_string(value)); }
    bool number_float(number_float_t, const string_t& text) override { return number(text); }
    bool string(string_t& value) override { return add(scalar(DocumentNode::Kind::Scalar, std::move(value), "string")); }
    bool binary(binary_t&) override { return false; }  // not JSON text
    bool start_object(std::size_t) override { return open(DocumentNode::Kind::Map); }
    bool key(string_t& name) override {
        open_.back().key = std::move(name);
        return true;
    }
    bool end_object() override { return close(); }
    bool start_array(std::size_t) override { return open(DocumentNode::Kind::Sequence); }
    bool end_array() override { return close(); }
    bool parse_error(std::size_t, const std::string& token, const nlohmann::detail::exception& error) override {
        // 1e999 is JSON, but no double: said as every other number past range is.
        constexpr int kNumberOverflow = 406;
        error_ = error.id == kNumberOverflow ? "must be finite, got " + token : std::string("not valid JSON: ") + error.what();
        return false;
    }

private:
    struct Open {
        DocumentNode node;
        std::string key;                                   // a map's key waiting for its value
        std::unordered_map<std::string, std::size_t> index;  // a map's keys so far, with their places
    };

    static DocumentNode scalar(DocumentNode::Kind kind, std::string text, std::string tag) {
        DocumentNode node;
        node.kind = kind;
        node.text = std::move(text);
        node.tag = std::move(tag);
        return node;
    }
    bool number(std::string text) { return add(scalar(DocumentNode::Kind::Scalar, std::move(text), "number")); }

    bool open(DocumentNode::Kind kind) {
        if (open_.size() >= static_cast<std::size_t>(kMaxDocumentDepth)) {
            error_ = "nested more than " + std::to_string(kMaxDocumentDepth) + " levels deep";
            refuse();
        }
        Open frame;
        frame.node.kind = kind;
        open_.push_back(std::move(frame));
        return true;
    }
    bool close() {
        DocumentNode done = std::move(open_.back().node);
        open_.pop_back();
        return add(std::move(done));
    }

    // Puts a finished value where it belongs: the root, an array's next item, or the value
    // of the key before it (in the place of an earlier value of the same key).
    bool add(DocumentNode node) {
        if (open_.empty()) {
            root_ = std::move(node);
            return true;
        }
        Open& parent = open_.back();
        if (parent.node.kind == DocumentNode::Kind::Sequence) {
            parent.node.items.push_back(std::move(node));
            return true;
        }
        const auto [place, is_new] = parent.index.emplace(parent.key, parent.node.items.size());
        if (is_new) {
            parent.node.keys.push_back(std::move(parent.key));
            parent.node.items.push_back(std::move(node));
        } else {
            parent.node.items[place->second] = std::move(node);
        }
        return true;
    }

    // The key path of the value being parsed: "\"intrinsics[0].fx\"", or nothing at the top.
    std::string where() const {
        std::string path;
        for (const Open& frame : open_) {
            if (frame.node.kind == DocumentNode::Kind::Sequence) {
                path += "[" + std::to_string(frame.node.items.size()) + "]";
            } else if (!frame.key.empty()) {
                path += (path.empty() ? "" : ".") + frame.key;
            }
        }
        return path.empty() ? "" : ": \"" + printable_text(path) + "\"";
    }

    const std::string& source_;
    std::vector<Open> open_;
    DocumentNode root_;
    std::string error_;
};

}  // namespace

DocumentNode parse_json_tree(std::string_view text, const std::string& source) {
    std::optional<DocumentNode> kept = take_kept_document(DocumentSyntax::Json, text, source);
    if (kept) return std::move(*kept);
    JsonTreeBuilder builder(source);
    if (!nlohmann::json::sax_parse(text.begin(), text.end(), &builder)) builder.refuse();
    return builder.take();
}

// ---- Field ----

namespace {

// A scalar as a message quotes it: a JSON string in JSON's quotes, a JSON number or
// boolean as it is, any other word in ''.
std::string quoted(const DocumentNode& scalar) {
    if (scalar.tag == "string") return shown_value(scalar.text, '"');
    if (scalar.tag == "number" || scalar.tag == "boolean") return printable_text(scalar.text, kShownValueLength);
    return shown_value(trim(scalar.text));
}

// What a value is, for a message that expected something else.
std::string show(const DocumentNode& node) {
    switch (node.kind) {
        case DocumentNode::Kind::Null: return node.tag == "null" ? "null" : "no value";
        case DocumentNode::Kind::Scalar: return quoted(node);
        case DocumentNode::Kind::Sequence: return "a list of " + std::to_string(node.items.size());
        case DocumentNode::Kind::Map: return "keys and values";
    }
    return "";
}

}  // namespace

Field::Field(const DocumentNode& node, std::string name, const std::string& source)
    : Field(node, std::move(name), &source) {}

Field::Field(const DocumentNode& node, std::string name, const std::string* source)
    : node_(&node), name_(std::move(name)), source_(source) {}

void Field::fail(const std::string& what) const {
    const std::string line = node_->line > 0 ? ": line " + std::to_string(node_->line) : "";
    if (name_.empty()) throw FileError(*source_ + line + ": " + what);
    throw FileError(*source_ + line + ": \"" + name_ + "\": " + what);
}

std::optional<Field> Field::find(std::initializer_list<std::string_view> keys) const {
    if (node_->kind != DocumentNode::Kind::Map) fail("expected keys and values, got " + show(*node_));
    for (std::string_view key : keys) {
        const DocumentNode* value = node_->find(key);
        if (value == nullptr || value->tag == "null") continue;
        Field found(*value, child_name(key), source_);
        if (value->kind == DocumentNode::Kind::Null) found.fail("has no value");
        return found;
    }
    return std::nullopt;
}

Field Field::at(std::initializer_list<std::string_view> keys) const {
    if (std::optional<Field> found = find(keys)) return *found;
    fail_at(*keys.begin(), "missing");
}

void Field::fail_at(std::string_view key, const std::string& what) const {
    static const DocumentNode absent;  // no line: the key is not there
    const DocumentNode* value = node_->find(key);
    Field(value != nullptr ? *value : absent, child_name(key), source_).fail(what);
}

std::size_t Field::size() const {
    if (node_->kind != DocumentNode::Kind::Sequence) fail("expected a list, got " + show(*node_));
    return node_->items.size();
}

Field Field::item(std::size_t index) const {
    if (index >= size()) fail("expected a list of at least " + std::to_string(index + 1) + ", got " + show(*node_));
    return Field(node_->items[index], name_ + "[" + std::to_string(index) + "]", source_);
}

std::string Field::child_name(std::string_view key) const {
    return name_.empty() ? std::string(key) : name_ + "." + std::string(key);
}

std::string Field::text() const {
    if (node_->kind != DocumentNode::Kind::Scalar) fail("expected a single value, got " + show(*node_));
    if (node_->tag == "number" || node_->tag == "boolean") fail("expected a string, got " + quoted(*node_));
    return node_->text;
}

std::string Field::shown() const { return libcam::show(*node_); }

std::optional<bool> Field::boolean() const {
    if (node_->tag != "boolean") return std::nullopt;
    return node_->text == "true";
}

double Field::number_at(const DocumentNode& scalar, std::size_t index, bool indexed) const {
    const auto fail = [&](const std::string& what) {
        // The field is named only for a message: a copy of its name for every number was
        // most of the time of reading a file of many numbers.
        if (!indexed) Field(scalar, name_, source_).fail(what);
        const std::string line = scalar.line > 0 ? ": line " + std::to_string(scalar.line) : "";
        throw FileError(*source_ + line + ": \"" + name_ + "\"[" + std::to_string(index) + "]: " + what);
    };
    if (scalar.kind != DocumentNode::Kind::Scalar || scalar.tag == "string") fail("expected a number, got " + show(scalar));
    std::string_view word = trim(scalar.text);
    const std::string_view written = word;
    if (word.starts_with('+')) word.remove_prefix(1);
    double value = 0;
    const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
    if (word.empty() || end != word.data() + word.size() || error == std::errc::invalid_argument) {
        // YAML's spellings of infinity and NaN, named as such.
        std::string lower(written);
        std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
        if (lower == ".inf" || lower == "+.inf" || lower == "-.inf" || lower == ".nan") {
            fail("must be finite, got " + std::string(written));
        }
        fail("expected a number, got " + quoted(scalar));
    }
    if (error == std::errc::result_out_of_range || !std::isfinite(value)) {
        fail("must be finite, got " + printable_text(written, kShownValueLength));
    }
    return value;
}

double Field::number() const { return number_at(*node_, 0, false); }

long long Field::integer(long long min, long long max) const {
    if (node_->kind != DocumentNode::Kind::Scalar || node_->tag == "string") fail("expected an integer, got " + show(*node_));
    std::string_view word = trim(node_->text);
    const std::string written(word);
    if (word.starts_with('+')) word.remove_prefix(1);
    long long value = 0;
    const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
    const bool digits_only = !word.empty() && end == word.data() + word.size();
    if (!digits_only || error == std::errc::invalid_argument) fail("expected an integer, got " + quoted(*node_));
    if (error == std::errc::result_out_of_range || value < min || value > max) {
        fail("must be in [" + std::to_string(min) + ", " + std::to_string(max) + "], got " +
             printable_text(written, kShownValueLength));
    }
    return value;
}

long long Field::whole_number(long long min, long long max) const {
    const double value = number();
    if (value != std::floor(value) || value < static_cast<double>(min) || value > static_cast<double>(max)) {
        fail("expected a whole number in [" + std::to_string(min) + ", " + std::to_string(max) + "], got " +
             printable_text(node_->text, kShownValueLength));
    }
    return static_cast<long long>(value);
}

std::vector<double> Field::numbers(std::size_t max_count) const {
    if (node_->kind == DocumentNode::Kind::Scalar) return {number()};
    if (node_->kind != DocumentNode::Kind::Sequence) fail("expected a list of numbers");
    if (node_->items.size() > max_count) {
        fail("too many numbers: " + std::to_string(node_->items.size()) + " (at most " + std::to_string(max_count) + ")");
    }
    std::vector<double> values;
    values.reserve(node_->items.size());
    for (std::size_t i = 0; i < node_->items.size(); ++i) values.push_back(number_at(node_->items[i], i, true));
    return values;
}

}  // namespace libcam
