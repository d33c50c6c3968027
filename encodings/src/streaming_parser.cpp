// StreamingParser: the VRML97 reader for bytes that arrive over time. The text (gunzipped
// as it comes) grows in one std::string; the Parser's lexer is re-pointed at it after each
// append. Only text up to the last whitespace or bracket byte received is parsed, so no
// token is cut, and top-level statements are parsed one at a time against one persistent
// top Scope. A statement whose parse looked at the end of that text (Lexer::hitEnd) while
// more may come is undone (lexer position, scene sizes, counters, DEF and PROTO names) and
// retried once the unparsed text has grown by half; the others are committed at once.
// X3D's XML encoding (first byte '<') goes through XmlToClassic, whose Classic VRML text is
// what grows in that string, at the XML's locations; a plain statement is built straight
// from its elements (Impl::build, Parser::buildXmlStatement) once the statements before
// it are parsed, and committed at once.
// X3D's JSON encoding (first byte '{') is not streamed: its bytes are collected in
// `scratch` and translated by JsonToClassic at finish(), then parsed as one piece.
#include "encodings/streaming_parser.hpp"

#include "gltf/detect.hpp"
#include "gltf/import.hpp"
#include "parser_impl.hpp"
#include "x3d_json.hpp"
#include "x3d_xml.hpp"
#include "x3d_xml_tree.hpp"

#include <zlib.h>

#include <algorithm>
#include <array>
#include <optional>

namespace gs::vrml {

namespace {

/// RFC 1952 gzip, inflated as the bytes come; the same checks and messages as
/// parsing::gunzipInto (which sees the whole stream at once).
class Gunzip {
 public:
  Gunzip(std::string url, std::size_t maxBytes) : url_(std::move(url)), max_(maxBytes) {}
  ~Gunzip() {
    if (started_) inflateEnd(&zs_);
  }
  Gunzip(const Gunzip&) = delete;
  Gunzip& operator=(const Gunzip&) = delete;

  /// Appends what `in` decompresses to to `out`. Throws ParseError on damaged data or
  /// when `out` would exceed the limit.
  void feed(std::string_view in, std::string& out) {
    if (!started_) {
      if (inflateInit2(&zs_, 16 + MAX_WBITS) != Z_OK) fail("zlib could not start");
      started_ = true;
    }
    const auto* p = reinterpret_cast<const unsigned char*>(in.data());
    std::size_t left = in.size();
    while (left > 0) {
      if (memberDone_) {
        // Another member may follow (concatenated gzip, RFC 1952 2.2); zero padding is
        // tolerated, anything else is trailing garbage.
        const unsigned char b = *p;
        if (trail_ == Trail::none && b == 0x1f) {
          trail_ = Trail::magic;
        } else if (trail_ == Trail::magic && b == 0x8b) {
          if (inflateReset(&zs_) != Z_OK) fail("zlib could not restart");
          memberDone_ = false;
          trail_ = Trail::none;
          static constexpr std::array<unsigned char, 2> kMagic = {0x1f, 0x8b};
          inflateFrom(kMagic.data(), kMagic.size(), out);
        } else if (trail_ != Trail::magic && b == 0) {
          trail_ = Trail::zeros;
        } else {
          fail("trailing bytes after the gzip data");
        }
        ++p;
        --left;
        continue;
      }
      constexpr std::size_t kMaxFeed = 1u << 30;  // avail_in is 32-bit
      const std::size_t used = inflateFrom(p, std::min(left, kMaxFeed), out);
      p += used;
      left -= used;
    }
  }

  bool tooLarge = false;  // the error thrown was the size limit

  /// The stream ended: throws when the gzip data stopped short.
  void finish() {
    if (!memberDone_) fail("truncated");
    if (trail_ == Trail::magic) fail("trailing bytes after the gzip data");
  }

 private:
  enum class Trail { none, magic, zeros };

  [[noreturn]] void fail(const std::string& why) {
    throw ParseError(Diagnostic{Severity::error, {url_, 0, 0}, "corrupt gzip data: " + why});
  }

  // Inflates up to `n` bytes at `in`; returns how many were used (fewer when a member
  // ends).
  std::size_t inflateFrom(const unsigned char* in, std::size_t n, std::string& out) {
    zs_.next_in = const_cast<unsigned char*>(in);
    zs_.avail_in = static_cast<uInt>(n);
    while (true) {
      zs_.next_out = buffer_.data();
      zs_.avail_out = static_cast<uInt>(buffer_.size());
      const int rc = inflate(&zs_, Z_NO_FLUSH);
      const std::size_t produced = buffer_.size() - zs_.avail_out;
      if (produced > max_ - std::min(max_, total_)) {
        tooLarge = true;
        throw ParseError(Diagnostic{Severity::error,
                                    {url_, 0, 0},
                                    "decompressed data exceeds " + std::to_string(max_) +
                                        " bytes (ParseLimits::maxInputBytes)"});
      }
      out.append(reinterpret_cast<const char*>(buffer_.data()), produced);
      total_ += produced;
      if (rc == Z_STREAM_END) {
        memberDone_ = true;
        break;
      }
      if ((rc != Z_OK && rc != Z_BUF_ERROR) || (rc == Z_BUF_ERROR && zs_.avail_in > 0))
        fail(zs_.msg != nullptr ? zs_.msg : "inflate failed");
      // All input taken and all output out (room was left): wait for more bytes.
      if (rc == Z_BUF_ERROR || (zs_.avail_in == 0 && zs_.avail_out > 0)) break;
    }
    const std::size_t used = n - zs_.avail_in;
    zs_.next_in = nullptr;
    zs_.avail_in = 0;
    return used;
  }

  std::string url_;
  std::size_t max_;
  std::size_t total_ = 0;  // bytes produced so far
  z_stream zs_{};
  bool started_ = false;
  bool memberDone_ = false;
  Trail trail_ = Trail::none;
  std::array<unsigned char, 1 << 16> buffer_{};
};

/// Whitespace ends every token (strings and comments aside, which the lexer reports as
/// cut), and a bracket is a whole token that ends the one before: text up to the last such
/// byte holds no partial number or name, and a node statement shows once its '}' is here.
bool endsTokens(char c) {
  return parsing::isSpace(c) || c == '}' || c == ']' || c == '{' || c == '[';
}

}  // namespace

struct StreamingParser::Impl final : parsing::XmlStatementBuilder {
  Impl(std::string u, ParseOptions o)
      : url(std::move(u)), user(std::move(o)), inner(user), ctx(inner) {
    inner.onRootNode = nullptr;  // called here, once a statement is committed
    ctx.loaded = &loaded;
    ctx.externInBackground = user.externProtosInBackground;
    scene.url = url;
  }

  std::string url;
  ParseOptions user;   // as given: onRootNode is called from here
  ParseOptions inner;  // what the parser sees
  parsing::Context ctx;
  Scene scene;

  enum class Kind { unknown, plain, gzip } kind = Kind::unknown;
  std::string head;  // the first byte, while the kind is unknown
  std::unique_ptr<Gunzip> gunzip;
  // The encoding, decided by the first byte of the text that is no space or BOM: '<' is
  // X3D's XML, whose bytes go to `xml` (through `scratch`) and whose translation is `text`.
  enum class Encoding { unknown, classic, xml, json, gltf } encoding = Encoding::unknown;
  std::unique_ptr<parsing::XmlToClassic> xml;
  std::unique_ptr<parsing::JsonToClassic> json;
  std::string scratch;
  std::string text;          // the text so far (decompressed; Classic VRML)
  std::size_t scanned = 0;   // bytes of `text` looked at for the two marks below
  std::size_t complete = 0;  // bytes up to and including the last one that ends tokens
  std::size_t firstEol = std::string::npos;  // the first CR or LF
  std::size_t plainBytes = 0;                // plain bytes received (counted past the limit)
  bool tooLarge = false;

  std::unique_ptr<parsing::Parser> parser;  // once the header has been read
  parsing::Scope top;
  parsing::ScopeUndo undo;
  std::vector<std::shared_ptr<parsing::ExternFile>> loaded;
  std::size_t parsed = 0;      // text consumed by committed statements
  std::size_t retryAt = 0;     // a statement cut short is retried once `complete` is here
  bool waitingExtern = false;  // the last statement tried waits for an EXTERNPROTO file
  bool finished = false;
  bool stopped = false;
  bool headerFailed = false;  // XML whose header (version) was refused: translated only

  void append(std::string_view bytes);
  std::string& sink() {
    return encoding == Encoding::xml || encoding == Encoding::json || encoding == Encoding::gltf
               ? scratch
               : text;
  }
  bool decide(bool final);
  void translated(bool final);
  void scanNew();
  bool readHeader(bool final);
  std::size_t parse(bool final, bool force = false);
  std::size_t guarded(std::string_view bytes, bool final);
  std::size_t guardedFeed(std::string_view bytes, bool final);
  bool build(const parsing::XNode& root, const parsing::XmlTreeInfo& info) override;
  std::size_t built = 0;  // root nodes added by build() during this feed
  void clearScene() {
    scene = Scene{};
    scene.url = url;
  }
  void stop(Diagnostic d) {
    scene.diagnostics.items.push_back(std::move(d));
    stopped = true;
  }
};

// Finds the first line end (the header) and where the complete text ends.
void StreamingParser::Impl::scanNew() {
  const std::size_t n = text.size();
  if (firstEol == std::string::npos) {
    const std::size_t eol = text.find_first_of("\r\n", scanned);
    if (eol != std::string::npos) firstEol = eol;
  }
  for (std::size_t i = n; i > scanned; --i) {
    if (endsTokens(text[i - 1])) {
      complete = i;
      break;
    }
  }
  scanned = n;
}

void StreamingParser::Impl::append(std::string_view bytes) {
  if (bytes.empty()) return;
  if (kind == Kind::unknown) {
    if (head.empty() && bytes.size() < 2) {
      head.assign(bytes);
      return;
    }
    std::string first = head;
    first.append(bytes.substr(0, 2 - first.size()));
    kind = base::isGzip(first) ? Kind::gzip : Kind::plain;
    if (kind == Kind::gzip) gunzip = std::make_unique<Gunzip>(url, user.limits.maxInputBytes);
    if (!head.empty()) {
      const std::string h = std::move(head);
      head.clear();
      append(h);
      if (stopped) return;
    }
  }
  if (kind == Kind::gzip) {
    gunzip->feed(bytes, sink());
    return;
  }
  plainBytes += bytes.size();
  if (tooLarge || plainBytes > user.limits.maxInputBytes) {
    // parseInto rejects such input whole: no scene, one error naming the whole size.
    if (!tooLarge) {
      tooLarge = true;
      stopped = true;
      clearScene();
      scene.diagnostics.items.push_back({});
      text.clear();
      text.shrink_to_fit();
    }
    scene.diagnostics.items.back() = Diagnostic{
        Severity::error,
        {url, 0, 0},
        "input of " + std::to_string(plainBytes) + " bytes exceeds ParseLimits::maxInputBytes"};
    return;
  }
  sink().append(bytes);
}

// Decides the encoding once the text shows its first meaningful byte (or at the end);
// false while it cannot yet. Switching to XML moves the bytes so far to the translator.
bool StreamingParser::Impl::decide(bool final) {
  if (encoding != Encoding::unknown) return true;
  // A GLB (binary glTF, magic "glTF") is collected whole, like a JSON document.
  if (!final && !text.empty() && text.size() < 4 && text[0] == 'g') return false;
  if (gltf::isGlb(text)) {
    encoding = Encoding::gltf;
    scratch = std::move(text);
    text.clear();
    return true;
  }
  bool decided = false;
  const bool isXml = parsing::looksLikeXml(text, decided);
  if (!decided && !final) return false;
  if (!isXml && parsing::looksLikeJson(text, decided)) {
    encoding = Encoding::json;
    scene.x3d.encoding = "JSON";
    scratch = std::move(text);
    text.clear();
    return true;
  }
  if (!isXml) {
    encoding = Encoding::classic;
    return true;
  }
  encoding = Encoding::xml;
  scene.x3d.encoding = "XML";
  xml = std::make_unique<parsing::XmlToClassic>(text, url, user.limits.maxNesting);
  if (parsing::xmlDirectBuild()) xml->setBuilder(this);
  scratch = std::move(text);
  text.clear();
  return true;
}

// After XML bytes arrived in `scratch`: translates them, and adds the translator's
// warnings (already at XML locations) to the scene.
void StreamingParser::Impl::translated(bool final) {
  xml->feed(scratch);
  scratch.clear();
  if (final) xml->finish();
  xml->addWarnings(scene);
}

bool StreamingParser::Impl::readHeader(bool final) {
  if (parser) return true;
  if (headerFailed || (firstEol == std::string::npos && !final)) return false;
  const std::string_view all(text);
  const std::size_t start = all.starts_with("\xEF\xBB\xBF") ? 3 : 0;
  const std::size_t eol = all.find_first_of("\r\n", start);
  const std::string_view line =
      all.substr(start, eol == std::string_view::npos ? std::string_view::npos : eol - start);
  std::string version;
  std::string problem = parsing::headerProblem(line, version);
  if (!problem.empty()) {
    Diagnostic d{Severity::error, {url, 1, 1}, std::move(problem)};
    if (!xml) {
      stop(std::move(d));
      return false;
    }
    // XML (an unsupported version): nothing is built, but the rest is still translated,
    // so that its warnings and syntax error come out as parseVrml gives them.
    headerFailed = true;
    scene.diagnostics.items.push_back(std::move(d));
    return false;
  }
  ctx.x3d = !version.empty();
  ctx.x3dVersion3 = version.starts_with("3");
  if (ctx.x3d) {
    scene.x3d.version = version;
    if (scene.x3d.encoding.empty()) scene.x3d.encoding = "Classic VRML";
  }
  top.x3d = &scene.x3d;
  const std::size_t begin = eol == std::string_view::npos ? all.size() : eol;
  parsing::TextOrigin* origin = xml ? &xml->origin() : json ? &json->origin() : nullptr;
  parser = std::make_unique<parsing::Parser>(all.substr(0, std::max(begin, complete)), url, begin,
                                             ctx, scene.diagnostics, 0, origin);
  top.routes = &scene.routes;
  top.hidden = &scene.hiddenNodes;
  top.declared = &scene.protos;
  top.checkRoots = true;
  top.undo = &undo;
  parsed = begin;
  return true;
}

// XML: a plain statement ended (XmlToClassic), to be built after the statements
// translated before it: those are parsed first (they are whole), and it is built once they
// all are, committed at once.
bool StreamingParser::Impl::build(const parsing::XNode& root, const parsing::XmlTreeInfo& info) {
  if (stopped) return false;
  scanNew();
  built += parse(false, true);
  if (stopped || !parser) return false;
  for (std::size_t i = parsed; i < text.size(); ++i)
    if (!parsing::isSpace(text[i])) return false;  // a statement waits for more text
  const std::size_t roots = scene.rootNodes.size();
  if (!parser->buildXmlStatement(top, root, info, scene.rootNodes)) return false;
  undo.defs.clear();
  undo.protos.clear();
  for (std::size_t i = roots; i < scene.rootNodes.size(); ++i) {
    ++built;
    if (user.onRootNode) user.onRootNode(scene.rootNodes[i]);
  }
  return true;
}

// Parses the statements now complete (`force`: even before the text has grown to retryAt).
std::size_t StreamingParser::Impl::parse(bool final, bool force) {
  if (stopped || !readHeader(final)) return 0;
  const std::size_t end = final ? text.size() : complete;
  if (!final && !force && end < retryAt) return 0;
  parser->extendText(std::string_view(text.data(), end), final);
  parsing::Lexer& lex = parser->lexer();
  std::size_t added = 0;
  while (true) {
    const parsing::Parser::State before = parser->state();
    const std::size_t roots = scene.rootNodes.size();
    const std::size_t routes = scene.routes.size();
    const std::size_t hidden = scene.hiddenNodes.size();
    const std::size_t protos = scene.protos.size();
    const X3dInfo x3dBefore = scene.x3d;  // a few short lists: the header statements
    const parsing::Context::Units unitsBefore = ctx.units;
    const std::size_t diags = scene.diagnostics.items.size();
    const std::size_t nodes = ctx.nodeCount;
    const std::size_t externs = loaded.size();
    lex.clearHitEnd();
    ctx.externPending = false;
    bool more = false;
    std::optional<ParseError> fatal;
    try {
      more = parser->parseTopStatement(top, scene.rootNodes);
    } catch (const ParseError& e) {
      fatal.emplace(e);
    }
    if (!final && (lex.hitEnd() || ctx.externPending)) {
      // Cut short by the end of the text so far, or needing an EXTERNPROTO file still on
      // its way: undo it all, wait for more (or for the file: retried at every feed).
      parser->restore(before);
      auto cut = [](auto& v, std::size_t n) {
        v.erase(v.begin() + static_cast<std::ptrdiff_t>(n), v.end());
      };
      cut(scene.rootNodes, roots);
      cut(scene.routes, routes);
      cut(scene.hiddenNodes, hidden);
      cut(scene.protos, protos);
      scene.x3d = x3dBefore;
      ctx.units = unitsBefore;
      cut(scene.diagnostics.items, diags);
      ctx.nodeCount = nodes;
      for (auto it = undo.defs.rbegin(); it != undo.defs.rend(); ++it) {
        if (it->second)
          top.defs[it->first] = std::move(*it->second);
        else
          top.defs.erase(it->first);
      }
      for (auto it = undo.protos.rbegin(); it != undo.protos.rend(); ++it) {
        if (it->second)
          top.protos[it->first] = std::move(*it->second);
        else
          top.protos.erase(it->first);
      }
      for (std::size_t i = externs; i < loaded.size(); ++i) loaded[i]->replay = true;
      loaded.resize(externs);
      undo.defs.clear();
      undo.protos.clear();
      const std::size_t start = before.position.offset;
      waitingExtern = ctx.externPending && !lex.hitEnd();
      retryAt = waitingExtern ? 0 : start + (end - start) * 3 / 2 + 1;
      break;
    }
    waitingExtern = false;
    undo.defs.clear();
    undo.protos.clear();
    parsed = lex.offset();
    for (std::size_t i = roots; i < scene.rootNodes.size(); ++i) {
      ++added;
      if (user.onRootNode) user.onRootNode(scene.rootNodes[i]);
    }
    if (fatal) {
      parser->endScene(&*fatal);
      stopped = true;
      break;
    }
    if (!more) {  // (before the end, the end of the text was seen: undone above)
      if (final) {
        parser->endScene(nullptr);
        stopped = true;
      }
      break;
    }
  }
  return added;
}

std::size_t StreamingParser::Impl::guarded(std::string_view bytes, bool final) {
  built = 0;
  const std::size_t added = guardedFeed(bytes, final);
  return added + built;
}

std::size_t StreamingParser::Impl::guardedFeed(std::string_view bytes, bool final) {
  try {
    if (stopped) {
      if (tooLarge) append(bytes);
      return 0;
    }
    try {
      append(bytes);
      if (final && kind == Kind::unknown) {  // fewer than two bytes: not gzip
        kind = Kind::plain;
        const std::string h = std::move(head);
        head.clear();
        append(h);
      }
      if (final && gunzip) gunzip->finish();
    } catch (const ParseError& e) {
      // Input over the size limit is rejected whole, as parseInto does; damaged gzip
      // data ends the parse, keeping what was read before.
      if (gunzip && gunzip->tooLarge) clearScene();
      stop(e.diagnostic);
      return 0;
    }
    if (stopped) return 0;
    if (!decide(final)) return 0;
    if (xml) {
      translated(final);
      if (xml->failed()) {
        // An XML syntax error ends the parse; the statements translated before it stay.
        std::size_t added = 0;
        if (xml->wroteHeader()) {
          scanNew();
          added = parse(true);
        }
        stop(xml->fatalError());
        return added;
      }
      if (!xml->wroteHeader()) return 0;  // (at the end, expat has failed: no element)
    }
    if (encoding == Encoding::gltf ||
        (encoding == Encoding::json && final && gltf::looksLikeGltfJson(scratch))) {
      if (!final) return 0;  // whole assets only
      const std::size_t before = scene.rootNodes.size();
      gltf::importGltf(scratch, url, parsing::gltfImportOptions(user), scene);
      scratch.clear();
      scratch.shrink_to_fit();
      stopped = true;
      return scene.rootNodes.size() - before;
    }
    if (encoding == Encoding::json) {
      if (!final) return 0;  // whole documents only
      json = std::make_unique<parsing::JsonToClassic>(text, url, user.limits.maxNesting);
      json->translate(scratch, scene);
      scratch.clear();
      scratch.shrink_to_fit();
      std::size_t added = 0;
      if (json->wroteHeader()) {
        scanNew();
        added = parse(true);
      }
      scene.x3d.encoding = "JSON";
      if (json->failed()) {
        stop(json->fatalError());
      } else if (!json->wroteHeader()) {
        stopped = true;
      }
      return added;
    }
    scanNew();
    return parse(final);
  } catch (const std::bad_alloc&) {
    stop(Diagnostic{Severity::error, {url, 0, 0}, "out of memory"});
    return 0;
  }
}

StreamingParser::StreamingParser(std::string url, ParseOptions options)
    : impl_(std::make_unique<Impl>(std::move(url), std::move(options))) {}

bool StreamingParser::rebase(std::string url) {
  Impl& m = *impl_;
  if (!m.text.empty() || !m.head.empty() || m.gunzip || m.parser || m.xml || !m.scratch.empty())
    return false;
  m.url = std::move(url);
  m.scene.url = m.url;
  return true;
}

StreamingParser::~StreamingParser() = default;

std::size_t StreamingParser::feed(std::string_view bytes) {
  if (impl_->finished) return 0;
  return impl_->guarded(bytes, false);
}

std::size_t StreamingParser::finish() {
  if (impl_->finished) return 0;
  impl_->finished = true;
  return impl_->guarded({}, true);
}

const Scene& StreamingParser::scene() const {
  return impl_->scene;
}

Scene StreamingParser::takeScene() {
  impl_->stopped = true;  // the parser's references into the scene go with it
  return std::move(impl_->scene);
}

std::size_t StreamingParser::textBytes() const {
  return impl_->tooLarge ? impl_->plainBytes : impl_->text.size();
}

std::size_t StreamingParser::parsedBytes() const {
  return impl_->parsed;
}

bool StreamingParser::waitingForExternProto() const {
  return impl_->waitingExtern && !done();
}

bool StreamingParser::done() const {
  return impl_->finished || impl_->stopped;
}

}  // namespace gs::vrml
