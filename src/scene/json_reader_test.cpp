// Hostile JSON input: nesting and size limits, and messages that quote user text (keys,
// names, file names) stay one short line (core/message_text.h).
#include "scene/json_reader.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/message_text.h"

namespace caligo {
namespace {

// The InputError that `f` throws, as text (a failure, and empty, if none).
template <typename F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected an InputError";
  return {};
}

bool has_raw_control_characters(const std::string& s) {
  for (char c : s)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) return true;
  return false;
}

// ---- quote_for_message / printable_for_message ------------------------------------------------

TEST(MessageText, ControlCharactersAreEscaped) {
  EXPECT_EQ(quote_for_message(std::string("a\nb\rc\td\0e\x1b[31mf\x7fg", 17)),
            "\"a\\nb\\rc\\td\\x00e\\x1b[31mf\\x7fg\"");
  EXPECT_EQ(quote_for_message("say \"hi\" \\o/"), "\"say \\\"hi\\\" \\\\o/\"");
  EXPECT_EQ(printable_for_message("say \"hi\" \\o/"), "say \"hi\" \\o/");  // unquoted: left alone
  // UTF-8 is kept; C1 controls (U+009B is a terminal's CSI) and invalid bytes are escaped.
  EXPECT_EQ(printable_for_message("caf\xc3\xa9 \xe2\x86\x92"), "caf\xc3\xa9 \xe2\x86\x92");
  EXPECT_EQ(printable_for_message("x\xc2\x9b"
                                  "1m"),
            "x\\u009b1m");
  EXPECT_EQ(printable_for_message("\xff\xc3(\xe2\x82"), "\\xff\\xc3(\\xe2\\x82");
  EXPECT_EQ(printable_for_message("\xc0\xaf"), "\\xc0\\xaf");  // overlong '/'
}

TEST(MessageText, LongTextIsAbbreviatedWithItsLength) {
  const std::string exact(80, 'k');
  EXPECT_EQ(quote_for_message(exact), "\"" + exact + "\"");
  const std::string key(1 << 20, 'k');
  const std::string q = quote_for_message(key);
  const std::string sixty(60, 'k');  // (a named string: GCC 12 warns falsely on "x" + temporary)
  EXPECT_EQ(q, "\"" + sixty + "... (1048576 bytes)\"");
  EXPECT_LE(q.size(), kMessageQuoteBytes + 2);
  // Escapes count towards the limit, and neither an escape nor a UTF-8 character is cut.
  std::string thirty_escapes;
  for (int i = 0; i < 30; ++i) thirty_escapes += "\\n";
  EXPECT_EQ(printable_for_message(std::string(1000, '\n')), thirty_escapes + "... (1000 bytes)");
  std::string accents;
  for (int i = 0; i < 100; ++i) accents += "\xc3\xa9";
  const std::string a = printable_for_message(" " + accents);  // odd offset: cuts fall mid-pair
  const std::string first_29 = accents.substr(0, 58);
  EXPECT_EQ(a, " " + first_29 + "... (201 bytes)");
}

TEST(MessageText, PrintableIsIdempotentSoMainCanApplyItAgain) {
  for (const std::string& s :
       {std::string("file\nname\x1b"), std::string(5000, 'x'), std::string("a\\nb \"q\"")}) {
    const std::string once = printable_for_message(s, kMessageLineBytes);
    if (s.size() <= kMessageLineBytes) {
      EXPECT_EQ(printable_for_message(once, kMessageLineBytes), once);
    }
    EXPECT_FALSE(has_raw_control_characters(once));
  }
}

TEST(MessageText, LocationsEscapeFileNamesAndAbbreviatePointerTokens) {
  const SourceLocation where{std::string("scene\n.json"), "/camera/" + std::string(100000, 'z') + "/2"};
  const std::string s = where.to_string();
  EXPECT_EQ(s.rfind("scene\\n.json: /camera/zzz", 0), 0u) << s.substr(0, 100);
  EXPECT_NE(s.find("... (100001 bytes)/2"), std::string::npos) << s;  // the token with its slash
  EXPECT_LT(s.size(), 120u);
  const SourceLocation nul{std::string("a\0b.json", 8), ""};
  EXPECT_EQ(nul.to_string(), "a\\x00b.json");
}

// ---- Limits -------------------------------------------------------------------------------

std::string nested_arrays(size_t depth) { return std::string(depth, '[') + std::string(depth, ']'); }

TEST(JsonLimits, NestingUpToTheLimitParses) {
  Json j = parse_json_text(nested_arrays(kMaxJsonDepth), "deep.json");
  size_t depth = 0;
  for (const Json* v = &j; v->is_array(); v = &(*v)[0]) {
    ++depth;
    if (v->empty()) break;
  }
  EXPECT_EQ(depth, kMaxJsonDepth);
}

TEST(JsonLimits, DeeperNestingIsALocatedError) {
  const std::string message =
      error_of([] { parse_json_text(nested_arrays(kMaxJsonDepth + 1), "deep.json"); });
  std::string pointer;
  for (size_t i = 0; i < kMaxJsonDepth; ++i) pointer += "/0";
  EXPECT_EQ(message,
            "deep.json: " + pointer + ": JSON nested more than 64 levels deep (the limit for scene files)");
  // Objects name their keys; the offending value is the one that opens level 65: levels alternate
  // object (even) and array (odd) below the root, so level 65 is the array of 31 "/a/1" down.
  std::string objects = R"({"camera": )";
  for (size_t i = 1; i < kMaxJsonDepth; ++i) objects += R"({"a": [1, )";
  std::string expected = "/camera";
  for (int i = 0; i < 31; ++i) expected += "/a/1";
  EXPECT_EQ(error_of([&] { parse_json_text(objects, "o.json"); }),
            "o.json: " + expected + "/a: JSON nested more than 64 levels deep (the limit for scene files)");
}

TEST(JsonLimits, HundredThousandLevelsFailWithoutRecursion) {
  // Before the limit, describing such a value in a message recursed 100,000 deep (SIGSEGV).
  const std::string message = error_of([] { parse_json_text(nested_arrays(100000), "deep.json"); });
  EXPECT_NE(message.find("nested more than 64 levels"), std::string::npos);
  std::string text;
  for (int i = 0; i < 100000; ++i) text += R"({"k":)";
  EXPECT_NE(error_of([&] { parse_json_text(text, "o.json"); }).find("nested more than 64 levels"),
            std::string::npos);
}

TEST(JsonLimits, TextOverTheSizeLimitIsRefused) {
  std::string text(kMaxJsonBytes + 1, ' ');
  text[0] = '1';
  EXPECT_EQ(error_of([&] { parse_json_text(text, "big.json"); }),
            "big.json: the file is 67108865 bytes; JSON input is limited to 67108864 bytes (64 MiB)");
  text.pop_back();  // exactly at the limit: parsed
  EXPECT_EQ(parse_json_text(text, "big.json"), Json(1));
}

// ---- Messages quoting user text -----------------------------------------------------------

TEST(JsonMessages, AMegabyteUnknownKeyGivesAShortLine) {
  const std::string key(1 << 20, 'q');
  const Json j = parse_json_text("{\"" + key + "\": 1}", "scene.json");
  const std::string message = error_of([&] {
    ObjectReader r(JsonCursor(j, "scene.json", ""), "a scene");
    r.allow({"camera", "render", "realtime", "materials", "shapes", "lights", "media", "volumes"});
  });
  EXPECT_LT(message.size(), 400u) << message;
  EXPECT_NE(message.find("unknown key \"qqqq"), std::string::npos) << message;
  EXPECT_NE(message.find("... (1048576 bytes)\" in a scene"), std::string::npos) << message;
  EXPECT_NE(message.find("allowed keys: camera,"), std::string::npos) << message;
}

TEST(JsonMessages, ControlCharactersInKeysAndNamesAreEscaped) {
  const Json j = parse_json_text(R"({"bad\nkey\u0000\u001b[2J": 1, "m": "no\nsuch\u007f"})", "s.json");
  const std::string unknown = error_of([&] {
    ObjectReader r(JsonCursor(j, "s.json", ""), "a scene");
    r.allow({"m"});
  });
  EXPECT_FALSE(has_raw_control_characters(unknown)) << unknown;
  EXPECT_NE(unknown.find("s.json: /bad\\nkey\\x00\\x1b[2J: unknown key \"bad\\nkey\\x00\\x1b[2J\""),
            std::string::npos)
      << unknown;
  const std::string missing = error_of([&] {
    find_definition(JsonCursor(j, "s.json", "").member("m"), {"glass", "metal"}, "material", "materials");
  });
  EXPECT_EQ(missing, "s.json: /m: unknown material \"no\\nsuch\\x7f\"; defined materials: glass, metal");
}

TEST(JsonMessages, DuplicateLongKeyIsAbbreviated) {
  const std::string key(5000, 'd');
  const std::string message =
      error_of([&] { parse_json_text("{\"" + key + "\": 1, \"" + key + "\": 2}", "dup.json"); });
  EXPECT_LT(message.size(), 250u) << message;
  EXPECT_NE(message.find("duplicate key \"ddd"), std::string::npos) << message;
}

}  // namespace
}  // namespace caligo
