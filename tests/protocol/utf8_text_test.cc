// Text for proto3 string fields (protocol/utf8_text.h), against RFC 3629:
// valid UTF-8 passes unchanged, and every byte outside a valid sequence is
// written as \xNN, so the result always parses as a string field.
#include <gtest/gtest.h>

#include "protocol/tessera.pb.h"
#include "protocol/utf8_text.h"

namespace tessera {
namespace {

TEST(Utf8Text, ValidTextPassesAndInvalidBytesAreEscaped) {
  for (const std::string& valid :
       {std::string(""), std::string("plain ascii"), std::string("15\xC2\xB0 (degrees)"),
        std::string("\xE2\x82\xAC euro"), std::string("\xF0\x9F\x99\x82 emoji"), std::string("\xEF\xBF\xBF"),
        std::string("\xF4\x8F\xBF\xBF")}) {
    EXPECT_TRUE(isValidUtf8(valid)) << valid;
    EXPECT_EQ(toValidUtf8(valid), valid);
  }
  const std::pair<std::string, std::string> invalid[] = {
      {std::string("a\xFF"
                   "b"),
       "a\\xFFb"},                                                // never in UTF-8
      {std::string("\xC0\x80"), "\\xC0\\x80"},                    // overlong NUL
      {std::string("\xED\xA0\x80"), "\\xED\\xA0\\x80"},           // a surrogate
      {std::string("\xF4\x90\x80\x80"), "\\xF4\\x90\\x80\\x80"},  // above U+10FFFF
      {std::string("cut \xE2\x82"), "cut \\xE2\\x82"},            // truncated at the end
      {std::string("\xE2\x82"
                   "A"),
       "\\xE2\\x82A"},  // truncated inside
      {std::string("\x80 lone continuation"), "\\x80 lone continuation"},
  };
  for (const auto& [bad, escaped] : invalid) {
    EXPECT_FALSE(isValidUtf8(bad)) << escaped;
    EXPECT_EQ(toValidUtf8(bad), escaped);
    EXPECT_TRUE(isValidUtf8(toValidUtf8(bad)));
    // What the escaping is for: a Reject carrying it parses.
    wire::ServerMessage m;
    m.mutable_reject()->set_message(toValidUtf8(bad));
    wire::ServerMessage back;
    EXPECT_TRUE(back.ParseFromString(m.SerializeAsString())) << escaped;
  }
}

}  // namespace
}  // namespace tessera
