// Minimal XML reader for the tests: elements, attributes, text; rejects unbalanced or
// malformed markup (throws std::runtime_error with the offset). Enough to check that the
// XDMF we write is well-formed and to walk its tree; not a general XML parser.
#pragma once
#include <cctype>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace cgdem::io::test {

struct XmlNode {
  std::string name, text;
  std::map<std::string, std::string> attr;
  std::vector<XmlNode> children;

  std::vector<const XmlNode*> all(const std::string& tag) const {  // descendants named tag
    std::vector<const XmlNode*> out;
    for (const XmlNode& c : children) {
      if (c.name == tag) out.push_back(&c);
      for (const XmlNode* d : c.all(tag)) out.push_back(d);
    }
    return out;
  }
};

class MiniXml {
 public:
  static XmlNode parse(const std::string& s) {
    MiniXml p(s);
    p.skip_prolog();
    XmlNode root = p.element();
    p.space();
    if (p.i_ != s.size()) p.fail("content after the root element");
    return root;
  }

 private:
  explicit MiniXml(const std::string& s) : s_(s) {}
  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error("XML error at offset " + std::to_string(i_) + ": " + what);
  }
  void space() {
    while (i_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[i_]))) ++i_;
  }
  bool starts(const char* t) const { return s_.compare(i_, std::char_traits<char>::length(t), t) == 0; }
  void skip_prolog() {
    for (space(); starts("<?") || starts("<!"); space()) {
      size_t e = s_.find('>', i_);
      if (e == std::string::npos) fail("unterminated declaration");
      i_ = e + 1;
    }
  }
  std::string name() {
    size_t b = i_;
    while (i_ < s_.size() && (std::isalnum(static_cast<unsigned char>(s_[i_])) || s_[i_] == '_' || s_[i_] == '-'))
      ++i_;
    if (b == i_) fail("expected a name");
    return s_.substr(b, i_ - b);
  }
  std::string unescape(const std::string& t) {
    std::string out;
    for (size_t k = 0; k < t.size(); ++k) {
      if (t[k] == '<') fail("'<' inside text or attribute");
      if (t[k] != '&') { out += t[k]; continue; }
      size_t e = t.find(';', k);
      if (e == std::string::npos) fail("unterminated entity");
      const std::string ent = t.substr(k, e - k + 1);
      static const std::map<std::string, char> known = {
          {"&amp;", '&'}, {"&lt;", '<'}, {"&gt;", '>'}, {"&quot;", '"'}, {"&apos;", '\''}};
      auto it = known.find(ent);
      if (it == known.end()) fail("unknown entity " + ent);
      out += it->second;
      k = e;
    }
    return out;
  }
  XmlNode element() {
    if (!starts("<")) fail("expected '<'");
    ++i_;
    XmlNode n;
    n.name = name();
    for (space(); !starts(">") && !starts("/>"); space()) {
      std::string key = name();
      space();
      if (!starts("=")) fail("expected '=' after attribute " + key);
      ++i_;
      space();
      if (!starts("\"")) fail("expected '\"'");
      size_t e = s_.find('"', i_ + 1);
      if (e == std::string::npos) fail("unterminated attribute value");
      if (n.attr.count(key)) fail("duplicate attribute " + key);
      n.attr[key] = unescape(s_.substr(i_ + 1, e - i_ - 1));
      i_ = e + 1;
    }
    if (starts("/>")) { i_ += 2; return n; }
    ++i_;
    while (true) {
      size_t lt = s_.find('<', i_);
      if (lt == std::string::npos) fail("unterminated element " + n.name);
      n.text += unescape(s_.substr(i_, lt - i_));
      i_ = lt;
      if (starts("</")) {
        i_ += 2;
        if (name() != n.name) fail("mismatched closing tag for " + n.name);
        space();
        if (!starts(">")) fail("expected '>'");
        ++i_;
        return n;
      }
      n.children.push_back(element());
    }
  }
  const std::string& s_;
  size_t i_ = 0;
};

}  // namespace cgdem::io::test
