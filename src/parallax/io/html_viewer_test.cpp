// The page's behaviour in a real browser is checked by tests/html_viewer_chromium_test.sh.
#include "parallax/io/html_viewer.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace parallax {
namespace {

size_t occurrences(const std::string& text, const std::string& needle) {
  size_t count = 0;
  for (size_t at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1))
    ++count;
  return count;
}

TEST(Base64, MatchesRfc4648TestVectors) {
  // RFC 4648, section 10.
  EXPECT_EQ(base64Encode(""), "");
  EXPECT_EQ(base64Encode("f"), "Zg==");
  EXPECT_EQ(base64Encode("fo"), "Zm8=");
  EXPECT_EQ(base64Encode("foo"), "Zm9v");
  EXPECT_EQ(base64Encode("foob"), "Zm9vYg==");
  EXPECT_EQ(base64Encode("fooba"), "Zm9vYmE=");
  EXPECT_EQ(base64Encode("foobar"), "Zm9vYmFy");
}

TEST(Base64, UsesTheWholeAlphabetForHighBytes) {
  // 0xFB 0xFF = 111110 111111 1111(00): '+' (62), '/' (63), '8' (60), padding.
  EXPECT_EQ(base64Encode("\xfb\xff"), "+/8=");
  EXPECT_EQ(base64Encode(std::string("\x00\x00\x00", 3)), "AAAA");
  EXPECT_EQ(base64Encode("\xff\xff\xff"), "////");
}

TEST(SliderPage, EmbedsEveryFrameAsADataUriWithNoExternalResources) {
  const std::vector<std::string> frames = {std::string("\x89PNG one\0", 9), "\x89PNG two",
                                           "\x89PNG three"};
  const std::string page = sliderPage("sweep", frames, {"eye -10", "eye 0", "eye +10"});
  EXPECT_EQ(page.rfind("<!DOCTYPE html>", 0), 0u);
  for (const std::string& frame : frames)
    EXPECT_EQ(occurrences(page, "data:image/png;base64," + base64Encode(frame) + "\""),
              frame == frames[0] ? 2u : 1u);  // frame 0 is also the image shown before scripts
  EXPECT_EQ(occurrences(page, "<img id=\"frame\""), 1u);
  EXPECT_EQ(occurrences(page, "data-frame=\"0\""), 1u);
  EXPECT_EQ(occurrences(page, "<input type=\"range\" id=\"slider\" min=\"0\" max=\"2\""), 1u);
  EXPECT_EQ(occurrences(page, "<span id=\"label\">eye -10</span>"), 1u);
  EXPECT_EQ(occurrences(page, "data-label=\"eye +10\""), 1u);
  for (const char* external : {"http:", "https:", "src=\"//", "<link", "<script src"})
    EXPECT_EQ(occurrences(page, external), 0u) << external;
}

TEST(SliderPage, EscapesTitleAndLabels) {
  const std::string page = sliderPage("<b>\"A&B\"</b>", {"x", "y"}, {"it's", "a<b"});
  EXPECT_EQ(occurrences(page, "<b>"), 0u);
  EXPECT_EQ(occurrences(page, "&lt;b&gt;&quot;A&amp;B&quot;&lt;/b&gt;"), 2u);  // title, h1
  EXPECT_EQ(occurrences(page, "data-label=\"it&#39;s\""), 1u);
  EXPECT_EQ(occurrences(page, "data-label=\"a&lt;b\""), 1u);
}

TEST(SliderPage, NamesFramesByIndexWithoutLabels) {
  const std::string page = sliderPage("t", {"a", "b"}, {});
  EXPECT_EQ(occurrences(page, "data-label=\"frame 1\""), 1u);
  EXPECT_EQ(occurrences(page, "max=\"1\""), 1u);
}

TEST(SliderPage, RejectsNoFramesOrMismatchedLabels) {
  EXPECT_THROW(sliderPage("t", {}, {}), std::invalid_argument);
  EXPECT_THROW(sliderPage("t", {"a", "b"}, {"one"}), std::invalid_argument);
}

}  // namespace
}  // namespace parallax
