// Bytes in for the parser: gzip and local files (base/gzip.hpp, base/file.hpp) with
// their errors as diagnostics, and the Inline self-reference check.
#include "parser_impl.hpp"

#include <filesystem>

#include "base/file.hpp"
#include "base/gzip.hpp"
#include "base/url.hpp"

namespace gs::vrml::parsing {

void gunzipInto(std::string_view bytes, const std::string& url, std::size_t maxBytes,
                std::string& out) {
  try {
    out = base::gunzip(bytes, maxBytes);
  } catch (const base::GzipError& e) {
    const std::string why = e.kind == base::GzipError::Kind::tooLarge
                                ? std::string(e.what()) + " (ParseLimits::maxInputBytes)"
                                : std::string(e.what());
    throw ParseError(Diagnostic{Severity::error, {url, 0, 0}, why});
  }
}

bool readFile(const std::string& url, std::size_t maxBytes, std::string& bytes,
              std::string& error) {
  return base::readFile(base::localPathOfUrl(url), bytes, error, maxBytes);
}

bool urlNamesFile(const std::string& base, const std::string& url) {
  if (base.empty() || base::hasScheme(base) || base::hasScheme(url) || url.empty() || url[0] == '#')
    return false;
  const std::string target = base::resolveUrl(base, url.substr(0, url.find('#')));
  std::error_code e1, e2;
  const auto a = std::filesystem::weakly_canonical(base, e1);
  const auto b = std::filesystem::weakly_canonical(target, e2);
  return !e1 && !e2 && a == b;
}

gltf::ImportOptions gltfImportOptions(const ParseOptions& options) {
  gltf::ImportOptions out;
  out.fetcher = options.fetcher;
  out.maxNesting = options.limits.maxNesting;
  out.maxNodes = options.limits.maxNodes;
  out.onRootNode = options.onRootNode;
  out.nodeType = [](std::string_view name) { return x3dNodeType(name); };
  return out;
}

}  // namespace gs::vrml::parsing

namespace gs::vrml {

std::string gunzipIfCompressed(std::string_view bytes, const std::string& url,
                               std::size_t maxBytes) {
  if (!base::isGzip(bytes)) return std::string(bytes);
  std::string out;
  parsing::gunzipInto(bytes, url, maxBytes, out);
  return out;
}

}  // namespace gs::vrml
