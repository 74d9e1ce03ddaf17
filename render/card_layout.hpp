// The layout of a card (a whole frame of text before or after a video's
// parts) in a frame of a given size: the largest of the two fonts that fit,
// lines wrapped at the right margin (a word wider than the frame broken), a
// table's label column set above its text when the columns leave it too
// little width, and pages when the text is taller than the frame. Pure: the
// fonts come as character widths and line heights, the drawing is
// SceneRenderer's.
#pragma once

#include <array>
#include <string>
#include <vector>

namespace gpm::render {

// A card. Each row is a line of text, or with more than one cell the row of
// a table whose columns line up; the last cell of a row wraps at the frame's
// right margin.
struct Card {
  std::string title;
  std::vector<std::vector<std::string>> rows;
  double seconds = 4.0;  // on screen (video seconds), all its pages
  bool large = false;    // the rows in the big font too (a short card)
};

// The two fonts of a card: width of each ASCII character and line height
// (px); characters outside 1..126 take no width (MuJoCo draws ASCII only).
struct CardFonts {
  std::array<int, 127> normal_w{}, big_w{};
  int normal_h = 0, big_h = 0;
};

enum class CardRole { kTitle, kLabel, kText, kPageMark };

// One text of a card line: font, left end (px from the frame's left) and role (its colour).
struct CardText {
  bool big = false;
  std::string text;
  int x = 0;
  CardRole role = CardRole::kText;
};

// A line of a card: its texts, its top (px from the frame's top) and height.
struct CardLine {
  std::vector<CardText> texts;
  int top = 0, height = 0;
};

// A page of a card: the title's lines, then its share of the rows' lines
// (and "2/3" at the bottom right when there is more than one page).
struct CardPage {
  std::vector<CardLine> lines;
};

// Width (px) of the longest line of t in a font (big or normal).
int card_text_px(const CardFonts& fonts, bool big, const std::string& t);

// The card laid out in a width x height frame: one page when it fits in the
// normal font, else as many as it needs (each at least the title and one
// line; a frame too small for that still gets pages of one line each). Every
// text lies within the margins.
std::vector<CardPage> lay_out_card(const Card& card, const CardFonts& fonts, int width, int height);

}  // namespace gpm::render
