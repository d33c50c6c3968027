// The lexer on its own (an internal class of gs_encodings, included from its source folder):
// tokens, identifier characters of annex A.2, numbers on the fast and slow paths, strings,
// and line/column computed lazily.
#include "../../encodings/src/lexer.hpp"

#include <catch2/catch.hpp>

#include <glm/glm.hpp>

#include <string>
#include <vector>

using gs::vrml::ParseError;
using gs::vrml::parsing::Lexer;
using gs::vrml::parsing::RecoverableError;
using gs::vrml::parsing::Tok;

TEST_CASE("lexer: token kinds, comments and commas are space", "[lexer]") {
  const std::string text = "DEF a-b+c { } [ ] , # note\n \"s\\\"x\" 12 -3 .5 . +4 'q";
  Lexer lx(text, "t.wrl");
  std::vector<Tok> kinds;
  std::vector<std::string> texts;
  for (;;) {
    auto t = lx.next();
    if (t.kind == Tok::end) break;
    kinds.push_back(t.kind);
    texts.emplace_back(t.text);
  }
  CHECK(kinds == std::vector<Tok>{Tok::id, Tok::id, Tok::lbrace, Tok::rbrace, Tok::lbracket,
                                  Tok::rbracket, Tok::string, Tok::number, Tok::number, Tok::number,
                                  Tok::period, Tok::number, Tok::other, Tok::id});
  CHECK(texts[1] == "a-b+c");
  CHECK(texts[6] == "\"s\\\"x\"");
}

TEST_CASE("lexer: identifier characters follow annex A.2", "[lexer]") {
  using gs::vrml::parsing::isIdFirst;
  using gs::vrml::parsing::isIdRest;
  for (char c : std::string("0123456789+-")) {
    CHECK(!isIdFirst(c));
    CHECK(isIdRest(c));
  }
  for (char c : std::string("\"#',.[\\]{} \t\n\x7f")) {
    CHECK(!isIdFirst(c));
    CHECK(!isIdRest(c));
  }
  for (char c : std::string("aZ_|!$%&()*/:;<=>?@^`~\xC3\xA9")) {
    CHECK(isIdFirst(c));
    CHECK(isIdRest(c));
  }
}

TEST_CASE("lexer: numbers near the end of input take the checked path", "[lexer]") {
  // Fewer than 24 bytes left: the inline path must not read past the end.
  for (const std::string t : {"1.5", "-2", "7", "0x1F", "3e2"}) {
    Lexer lx(t, "n");
    if (t == "0x1F")
      CHECK(lx.readInt32() == 31);
    else
      CHECK(lx.readFloat() == std::stof(t));
    CHECK(lx.atEnd());
  }
  Lexer list("1 2 3 4 5 6]", "l");
  std::vector<glm::vec3> v;
  list.readFloatsUntilBracket<3>(v);
  CHECK(v == std::vector<glm::vec3>{{1, 2, 3}, {4, 5, 6}});
  Lexer ints("0,1,-1, 22 ,-333]", "i");
  std::vector<std::int32_t> iv;
  ints.readInt32sUntilBracket(iv);
  CHECK(iv == std::vector<std::int32_t>{0, 1, -1, 22, -333});
}

TEST_CASE("lexer: bad numbers are recoverable errors, end of input is fatal", "[lexer]") {
  Lexer a("abc", "a");
  CHECK_THROWS_AS(a.readFloat(), RecoverableError);
  Lexer inf("inf", "b");
  CHECK_THROWS_AS(inf.readFloat(), RecoverableError);
  Lexer nan("-nan 1", "c");
  CHECK_THROWS_AS(nan.readFloat(), RecoverableError);
  Lexer e("", "d");
  try {
    e.readFloat();
    FAIL("no error");
  } catch (const RecoverableError&) {
    FAIL("end of input must be fatal");
  } catch (const ParseError& err) {
    CHECK(err.diagnostic.message == "expected a number, got end of file");
  }
  Lexer f("1.5", "f");
  CHECK_THROWS_AS(f.readInt32(), RecoverableError);
}

TEST_CASE("lexer: line and column are computed on demand", "[lexer]") {
  const std::string text = "ab\ncd\r\nef\rgh\n\nij";
  Lexer lx(text, "x.wrl");
  auto at = [&](std::size_t off) {
    const auto l = lx.locationAt(off);
    return std::pair<int, int>(l.line, l.column);
  };
  CHECK(at(0) == std::pair(1, 1));
  CHECK(at(4) == std::pair(2, 2));
  CHECK(at(7) == std::pair(3, 1));
  CHECK(at(10) == std::pair(4, 1));  // lone CR ends a line too
  CHECK(at(14) == std::pair(6, 1));
  CHECK(at(1) == std::pair(1, 2));  // going back resets the cache
  CHECK(lx.locationAt(3).file == "x.wrl");
  CHECK(lx.describeAt(text.size()) == "end of file");
  CHECK(lx.describeAt(3) == "'cd'");
}

TEST_CASE("lexer: skipBalanced skips nested groups and strings with brackets", "[lexer]") {
  Lexer lx("{ a [ b { \"}]\" } ] } next", "s");
  lx.skipBalanced();
  CHECK(lx.next().text == "next");
  Lexer open("{ [ ", "o");
  CHECK_THROWS_AS(open.skipBalanced(), ParseError);
}
