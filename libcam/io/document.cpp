#include "libcam/io/document.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <pugixml.hpp>
#include <system_error>

#include "libcam/error.hpp"

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
    [[noreturn]] void refuse(int line, const std::string& what) const {
        throw FileError(source_ + (line > 0 ? ": line " + std::to_string(line) : "") + ": " + what);
    }

private:
    const std::string& source_;
    std::size_t nodes_ = 0;
};

// ---- YAML (yaml-cpp) ----

std::string yaml_tag(const std::string& tag) {
    constexpr std::string_view kCore = "tag:yaml.org,2002:";  // what "!!" stands for
    if (tag == "?" || tag == "!") return "";                  // untagged (plain or quoted)
    if (std::string_view(tag).starts_with(kCore)) return tag.substr(kCore.size());
    return tag;
}

DocumentNode from_yaml(const YAML::Node& node, int depth, TreeBudget& budget) {
    DocumentNode out;
    out.line = node.Mark().is_null() ? 0 : node.Mark().line + 1;
    budget.enter(depth, out.line);
    switch (node.Type()) {
        case YAML::NodeType::Undefined:
        case YAML::NodeType::Null: break;
        case YAML::NodeType::Scalar:
            out.kind = DocumentNode::Kind::Scalar;
            out.text = node.Scalar();
            out.tag = yaml_tag(node.Tag());
            break;
        case YAML::NodeType::Sequence:
            out.kind = DocumentNode::Kind::Sequence;
            out.tag = yaml_tag(node.Tag());
            for (const YAML::Node& item : node) out.items.push_back(from_yaml(item, depth + 1, budget));
            break;
        case YAML::NodeType::Map:
            out.kind = DocumentNode::Kind::Map;
            out.tag = yaml_tag(node.Tag());
            for (const auto& entry : node) {
                const int key_line = entry.first.Mark().is_null() ? out.line : entry.first.Mark().line + 1;
                if (!entry.first.IsScalar()) budget.refuse(key_line, "a key that is not text");
                std::string key = entry.first.Scalar();
                if (out.find(key) != nullptr) budget.refuse(key_line, "the key \"" + key + "\" appears twice");
                out.items.push_back(from_yaml(entry.second, depth + 1, budget));
                out.keys.push_back(std::move(key));
            }
            break;
    }
    return out;
}

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
        for (const pugi::xml_node& child : children) {
            if (!sequence) {
                const std::string key = child.name();
                if (out.find(key) != nullptr) {
                    budget.refuse(lines.line_of(child.offset_debug()), "the element <" + key + "> appears twice");
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
    const std::string_view trimmed = [&] {
        std::string_view view(text);
        while (!view.empty() && is_space(view.front())) view.remove_prefix(1);
        while (!view.empty() && is_space(view.back())) view.remove_suffix(1);
        return view;
    }();
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

std::string_view trim(std::string_view text) {
    while (!text.empty() && is_space(text.front())) text.remove_prefix(1);
    while (!text.empty() && is_space(text.back())) text.remove_suffix(1);
    return text;
}

}  // namespace

DocumentNode parse_yaml_document(std::string_view text, const std::string& source) {
    const std::string yaml = without_yaml_header(text);
    std::vector<YAML::Node> documents;
    try {
        documents = YAML::LoadAll(yaml);
    } catch (const YAML::Exception& error) {
        const std::string where = error.mark.is_null() ? "" : ": line " + std::to_string(error.mark.line + 1);
        throw FileError(source + where + ": not valid YAML: " + error.msg);
    } catch (const std::exception& error) {
        throw FileError(source + ": not valid YAML: " + error.what());
    }
    if (documents.size() > 1) throw FileError(source + ": holds " + std::to_string(documents.size()) + " YAML documents, expected one");
    TreeBudget budget(source);
    DocumentNode tree = documents.empty() ? DocumentNode{} : from_yaml(documents.front(), 0, budget);
    // YAML has no closing bracket to show that a file is whole; a file cut short within
    // its last key ("distortion_coeffici") reads as that key with no value. Refused, so
    // that a cut file never reads as a camera without its last field.
    if (tree.kind == DocumentNode::Kind::Map && !tree.items.empty() && tree.items.back().kind == DocumentNode::Kind::Null) {
        throw FileError(source + ": the file ends with the key \"" + tree.keys.back() +
                        "\" and no value (is it cut short?)");
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
                        std::string(root.name()) + ">");
    }
    TreeBudget budget(source);
    DocumentNode tree = from_xml(root, 0, budget, lines);
    if (tree.kind == DocumentNode::Kind::Null) tree.kind = DocumentNode::Kind::Map;  // <opencv_storage/>: no keys
    if (tree.kind != DocumentNode::Kind::Map) throw FileError(source + ": <opencv_storage> holds no keys");
    return tree;
}

// ---- Field ----

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
    if (node_->kind != DocumentNode::Kind::Map) fail("expected keys and values");
    for (std::string_view key : keys) {
        if (const DocumentNode* value = node_->find(key)) {
            Field found(*value, name_.empty() ? std::string(key) : name_ + "." + std::string(key), source_);
            if (value->kind == DocumentNode::Kind::Null) found.fail("has no value");
            return found;
        }
    }
    return std::nullopt;
}

Field Field::at(std::initializer_list<std::string_view> keys) const {
    if (std::optional<Field> found = find(keys)) return *found;
    const std::string key(*keys.begin());
    const std::string name = name_.empty() ? key : name_ + "." + key;
    throw FileError(*source_ + ": \"" + name + "\": missing");
}

std::string Field::text() const {
    if (node_->kind != DocumentNode::Kind::Scalar) fail("expected a single value");
    return node_->text;
}

double Field::number_at(const DocumentNode& scalar, std::size_t index, bool indexed) const {
    const Field where(scalar, name_, source_);
    const auto fail = [&](const std::string& what) {
        if (!indexed) where.fail(what);
        const std::string line = scalar.line > 0 ? ": line " + std::to_string(scalar.line) : "";
        throw FileError(*source_ + line + ": \"" + name_ + "\"[" + std::to_string(index) + "]: " + what);
    };
    if (scalar.kind != DocumentNode::Kind::Scalar) fail("expected a number");
    std::string_view word = trim(scalar.text);
    const std::string_view quoted_word = word;
    if (word.starts_with('+')) word.remove_prefix(1);
    double value = 0;
    const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
    if (word.empty() || end != word.data() + word.size() || error == std::errc::invalid_argument) {
        // YAML's spellings of infinity and NaN, named as such.
        std::string lower(quoted_word);
        std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
        if (lower == ".inf" || lower == "+.inf" || lower == "-.inf" || lower == ".nan") {
            fail("must be finite, got " + std::string(quoted_word));
        }
        fail("expected a number, got '" + std::string(quoted_word) + "'");
    }
    if (error == std::errc::result_out_of_range || !std::isfinite(value)) {
        fail("must be finite, got " + std::string(quoted_word));
    }
    return value;
}

double Field::number() const { return number_at(*node_, 0, false); }

long long Field::integer(long long min, long long max) const {
    if (node_->kind != DocumentNode::Kind::Scalar) fail("expected an integer");
    std::string_view word = trim(node_->text);
    const std::string shown(word);
    if (word.starts_with('+')) word.remove_prefix(1);
    long long value = 0;
    const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
    const bool digits_only = !word.empty() && end == word.data() + word.size();
    if (!digits_only || error == std::errc::invalid_argument) fail("expected an integer, got '" + shown + "'");
    if (error == std::errc::result_out_of_range || value < min || value > max) {
        fail("must be in [" + std::to_string(min) + ", " + std::to_string(max) + "], got " + shown);
    }
    return value;
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
