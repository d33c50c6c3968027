// base/url.hpp: RFC 3986 resolution (the examples of section 5.4), local paths of URLs,
// schemes and mayReference.
#include <catch2/catch.hpp>

#include "base/url.hpp"

using gs::base::resolveUrl;

TEST_CASE("resolveUrl: RFC 3986 5.4.1 normal examples", "[base][url]") {
  const char* base = "http://a/b/c/d;p?q";
  // "g:h" -> "g:h" in the RFC; one-letter schemes are drive letters here, so a
  // two-letter scheme stands in for it.
  CHECK(resolveUrl(base, "gg:h") == "gg:h");
  CHECK(resolveUrl(base, "g") == "http://a/b/c/g");
  CHECK(resolveUrl(base, "./g") == "http://a/b/c/g");
  CHECK(resolveUrl(base, "g/") == "http://a/b/c/g/");
  CHECK(resolveUrl(base, "/g") == "http://a/g");
  CHECK(resolveUrl(base, "//g") == "http://g");
  CHECK(resolveUrl(base, "?y") == "http://a/b/c/d;p?y");
  CHECK(resolveUrl(base, "g?y") == "http://a/b/c/g?y");
  CHECK(resolveUrl(base, "#s") == "http://a/b/c/d;p?q#s");
  CHECK(resolveUrl(base, "g#s") == "http://a/b/c/g#s");
  CHECK(resolveUrl(base, "g?y#s") == "http://a/b/c/g?y#s");
  CHECK(resolveUrl(base, ";x") == "http://a/b/c/;x");
  CHECK(resolveUrl(base, "g;x") == "http://a/b/c/g;x");
  CHECK(resolveUrl(base, "g;x?y#s") == "http://a/b/c/g;x?y#s");
  CHECK(resolveUrl(base, "") == "http://a/b/c/d;p?q");
  CHECK(resolveUrl(base, ".") == "http://a/b/c/");
  CHECK(resolveUrl(base, "./") == "http://a/b/c/");
  CHECK(resolveUrl(base, "..") == "http://a/b/");
  CHECK(resolveUrl(base, "../") == "http://a/b/");
  CHECK(resolveUrl(base, "../g") == "http://a/b/g");
  CHECK(resolveUrl(base, "../..") == "http://a/");
  CHECK(resolveUrl(base, "../../") == "http://a/");
  CHECK(resolveUrl(base, "../../g") == "http://a/g");
}

TEST_CASE("resolveUrl: RFC 3986 5.4.2 abnormal examples", "[base][url]") {
  const char* base = "http://a/b/c/d;p?q";
  CHECK(resolveUrl(base, "../../../g") == "http://a/g");
  CHECK(resolveUrl(base, "../../../../g") == "http://a/g");
  CHECK(resolveUrl(base, "/./g") == "http://a/g");
  CHECK(resolveUrl(base, "/../g") == "http://a/g");
  CHECK(resolveUrl(base, "g.") == "http://a/b/c/g.");
  CHECK(resolveUrl(base, ".g") == "http://a/b/c/.g");
  CHECK(resolveUrl(base, "g..") == "http://a/b/c/g..");
  CHECK(resolveUrl(base, "..g") == "http://a/b/c/..g");
  CHECK(resolveUrl(base, "./../g") == "http://a/b/g");
  CHECK(resolveUrl(base, "./g/.") == "http://a/b/c/g/");
  CHECK(resolveUrl(base, "g/./h") == "http://a/b/c/g/h");
  CHECK(resolveUrl(base, "g/../h") == "http://a/b/c/h");
  CHECK(resolveUrl(base, "g;x=1/./y") == "http://a/b/c/g;x=1/y");
  CHECK(resolveUrl(base, "g;x=1/../y") == "http://a/b/c/y");
  CHECK(resolveUrl(base, "g?y/./x") == "http://a/b/c/g?y/./x");
  CHECK(resolveUrl(base, "g?y/../x") == "http://a/b/c/g?y/../x");
  CHECK(resolveUrl(base, "g#s/./x") == "http://a/b/c/g#s/./x");
  CHECK(resolveUrl(base, "g#s/../x") == "http://a/b/c/g#s/../x");
  CHECK(resolveUrl(base, "http:g") == "http:g");  // strict parsers (RFC 3986 5.4.2)
}

TEST_CASE("resolveUrl: local paths and worlds", "[base][url]") {
  CHECK(resolveUrl("/a/b/world.wrl", "tex.png") == "/a/b/tex.png");
  CHECK(resolveUrl("/a/b/world.wrl", "../c/./x.wrl") == "/a/c/x.wrl");
  CHECK(resolveUrl("/a/b/world.wrl", "/abs/x.wrl") == "/abs/x.wrl");
  CHECK(resolveUrl("world.wrl", "sub/x.wrl") == "sub/x.wrl");
  CHECK(resolveUrl("dir/world.wrl", "../../x.wrl") == "../x.wrl");
  CHECK(resolveUrl("http://h.org/w/world.wrl", "/protos/a.wrl") == "http://h.org/protos/a.wrl");
  CHECK(resolveUrl("http://h.org/w/world.wrl", "../x.png") == "http://h.org/x.png");
  CHECK(resolveUrl("file:///a/b/w.wrl", "c.wrl") == "file:///a/b/c.wrl");
  CHECK(resolveUrl("file:///a/b/w.wrl", "/c.wrl") == "file:///c.wrl");
}

TEST_CASE("localPathOfUrl, schemes and mayReference", "[base][url]") {
  using namespace gs::base;
  CHECK(localPathOfUrl("/a/b.wrl") == "/a/b.wrl");
  CHECK(localPathOfUrl("file:///a/my%20b.wrl") == "/a/my b.wrl");
  CHECK(localPathOfUrl("FILE://localhost/a/b.wrl") == "/a/b.wrl");
  CHECK(localPathOfUrl("file:/a/b.wrl") == "/a/b.wrl");
  CHECK(localPathOfUrl("http://h.org/x.wrl").empty());
  CHECK(localPathOfUrl("C:/x.wrl") == "C:/x.wrl");  // a drive letter, not a scheme
  CHECK(schemeOf("HTTPS://h/a") == "https");
  CHECK(schemeOf("/tmp/http://x").empty());
  CHECK(isHttpUrl("http://h/a.wrl"));
  CHECK(isHttpUrl("HTTPS://h/a.wrl"));
  CHECK_FALSE(isHttpUrl("file:///a.wrl"));
  CHECK_FALSE(isHttpUrl("/tmp/http://x"));
  CHECK_FALSE(isHttpUrl("httpx://h"));
  CHECK(withoutQueryOrFragment("http://h/a.qnv?x=1#y") == "http://h/a.qnv");

  std::string error;
  CHECK(mayReference("/home/me/a.wrl", "/etc/passwd", error));
  CHECK(mayReference("/home/me/a.wrl", "http://h/b.wrl", error));
  CHECK(mayReference("file:///home/me/a.wrl", "file:///etc/passwd", error));
  CHECK(mayReference("http://h/a.wrl", "https://other/b.qnv", error));
  CHECK(mayReference("https://h/a.wrl", "HTTP://h/b.wrl", error));
  CHECK(error.empty());
  CHECK_FALSE(mayReference("http://h/a.wrl", "file:///etc/passwd", error));
  CHECK(error ==
        "http://h/a.wrl may not reference 'file:///etc/passwd': content from the "
        "network may only reference http(s) URLs");
  CHECK_FALSE(mayReference("https://h/a.wrl", "/etc/passwd", error));
  CHECK_THAT(error, Catch::Contains("'/etc/passwd'"));
  CHECK_FALSE(mayReference("http://h/a.wrl", "ftp://h/b.wrl", error));
}

TEST_CASE("percentEncodePath writes a file's name as a URL's path", "[base][url]") {
  using gs::base::percentDecode;
  using gs::base::percentEncodePath;
  CHECK(percentEncodePath("buffers/bunny small.bin") == "buffers/bunny%20small.bin");
  CHECK(percentEncodePath("a%b?c#d\"e") == "a%25b%3Fc%23d%22e");
  CHECK(percentEncodePath("caf\xC3\xA9-1_2.~(x)") == "caf%C3%A9-1_2.~(x)");
  for (const std::string name : {"x y/z%20w.bin", "\x01\xFF", "plain.bin", ""})
    CHECK(percentDecode(percentEncodePath(name)) == name);
  // A ':' in the first segment would be a scheme; after a '/' it is a path's.
  CHECK(percentEncodePath("evil:x/a:b") == "evil%3Ax/a:b");
  CHECK_FALSE(gs::base::hasScheme(percentEncodePath("evil:x")));
  // Resolved against a scene's URL, as a side file is.
  CHECK(gs::base::resolveUrl("http://h/s/scene.gltf", percentEncodePath("b/my file.bin")) ==
        "http://h/s/b/my%20file.bin");
}
