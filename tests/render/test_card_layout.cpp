// Tests of render/card_layout.cpp: with fonts of known widths (8 px a
// character, 18 and 37 px lines, as MuJoCo's overlay), every word of a card
// is laid out once, in order, within the frame's margins, on as few pages as
// the line heights allow.
#include <sstream>

#include <gtest/gtest.h>

#include "render/card_layout.hpp"

namespace gpm::render {
namespace {

CardFonts fixed_fonts() {
  CardFonts f;
  f.normal_w.fill(8);
  f.big_w.fill(16);
  f.normal_h = 18;
  f.big_h = 37;
  return f;
}

Card long_card() {
  return Card{"GPM2002: calibration on its digital twin",
              {{"robot", "GPM2002, a 3-RRR planar parallel robot, simulated in MuJoCo"},
               {"procedure", "Accuracy-first calibration of the GPM2002 on the realistic twin, with compensation"},
               {"file", "scenarios/a_very_long_scenario_file_name_without_any_space_in_it_at_all.yaml"},
               {""},
               {"error (RMS)", "nominal", "calibrated"},
               {"at 12 poses", "9.68 mm", "10.2 um"}},
              5.0};
}

// The words of a card's rows in order (the title's excepted).
std::vector<std::string> words_of(const Card& c) {
  std::vector<std::string> out;
  for (const auto& row : c.rows)
    for (const std::string& cell : row) {
      std::istringstream in(cell);
      for (std::string w; in >> w;) out.push_back(w);
    }
  return out;
}

TEST(CardLayout, EveryWordOnceInOrderWithinTheMargins) {
  const CardFonts f = fixed_fonts();
  const Card card = long_card();
  for (const auto& [w, h] : {std::pair{320, 240}, {640, 480}, {1280, 720}}) {
    const std::vector<CardPage> pages = lay_out_card(card, f, w, h);
    const int margin = std::max(8, w / 24);
    std::string laid;  // the rows' text as laid out, pages and lines in order
    for (const CardPage& p : pages) {
      for (const CardLine& l : p.lines) {
        EXPECT_GE(l.top, margin) << w << "x" << h;
        EXPECT_LE(l.top + l.height, h - margin) << w << "x" << h << ": below the bottom margin";
        for (const CardText& t : l.texts) {
          EXPECT_GE(t.x, margin);
          EXPECT_LE(t.x + card_text_px(f, t.big, t.text), w - margin) << w << "x" << h << ": '" << t.text << "'";
          if (t.role == CardRole::kLabel || t.role == CardRole::kText) laid += t.text + " ";
        }
      }
    }
    // Broken words come back whole when the pieces are joined.
    std::string joined;
    for (const std::string& word : words_of(card)) joined += word;
    std::string laid_joined;
    for (const char c : laid)
      if (c != ' ') laid_joined += c;
    EXPECT_EQ(laid_joined, joined) << w << "x" << h;
  }
}

// 640x480 holds the card in one page, 320x240 does not (lines of 22 px):
// there every page repeats the title and is marked k/n.
TEST(CardLayout, PagesOnlyWhenTheCardIsTallerThanTheFrame) {
  const CardFonts f = fixed_fonts();
  EXPECT_EQ(lay_out_card(long_card(), f, 640, 480).size(), 1u);
  const std::vector<CardPage> pages = lay_out_card(long_card(), f, 320, 240);
  ASSERT_GE(pages.size(), 2u);
  for (size_t k = 0; k < pages.size(); ++k) {
    EXPECT_EQ(pages[k].lines.front().texts.front().role, CardRole::kTitle) << "page " << k;
    EXPECT_EQ(pages[k].lines.back().texts.front().text, std::to_string(k + 1) + "/" + std::to_string(pages.size()));
  }
  const Card short_card{"before and after", {{"", "nominal", "calibrated"}}, 5.0, true};
  const std::vector<CardPage> one = lay_out_card(short_card, f, 640, 480);
  ASSERT_EQ(one.size(), 1u);
  EXPECT_TRUE(one[0].lines.back().texts.back().big) << "a large short card in the big font";
}

}  // namespace
}  // namespace gpm::render
