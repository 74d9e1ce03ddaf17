// Card layout (render/card_layout.hpp).
#include "render/card_layout.hpp"

#include <algorithm>

#include <fmt/format.h>

namespace gpm::render {
namespace {

// Line advance of a font (px): the big font's a third more than its height, the normal font's a quarter.
int pitch_of(const CardFonts& f, bool big) { return big ? f.big_h + f.big_h / 3 : f.normal_h + f.normal_h / 4; }

int char_px(const CardFonts& f, bool big, char c) {
  return c > 0 && c < 127 ? (big ? f.big_w : f.normal_w)[static_cast<size_t>(c)] : 0;
}

// The pieces of word at most max_px wide each (a word wider than the frame is broken between characters).
std::vector<std::string> break_word(const CardFonts& f, bool big, const std::string& word, int max_px) {
  std::vector<std::string> out(1);
  int w = 0;
  for (const char c : word) {
    const int cw = char_px(f, big, c);
    if (w + cw > max_px && !out.back().empty()) out.emplace_back(), w = 0;
    out.back() += c;
    w += cw;
  }
  return out;
}

// t broken at spaces into lines at most max_px wide (one line for an empty t).
std::vector<std::string> wrap(const CardFonts& f, bool big, const std::string& t, int max_px) {
  std::vector<std::string> lines;
  std::string line;
  const auto add = [&](const std::string& piece) {
    if (!line.empty() && card_text_px(f, big, line + " " + piece) > max_px) lines.push_back(line), line.clear();
    line = line.empty() ? piece : line + " " + piece;
  };
  std::string word;
  const auto flush = [&] {
    if (word.empty()) return;
    const std::vector<std::string> pieces = break_word(f, big, word, max_px);
    for (size_t i = 0; i < pieces.size(); ++i) {
      if (i > 0) lines.push_back(line), line.clear();
      add(pieces[i]);
    }
    word.clear();
  };
  for (const char c : t) c == ' ' ? flush() : void(word += c);
  flush();
  if (!line.empty() || lines.empty()) lines.push_back(line);
  return lines;
}

// The lines of a card before they are put on pages: each with its row
// (-1 for the title) and its top as if on one endless page.
struct Flow {
  std::vector<CardLine> lines;
  std::vector<int> row;  // per line
  int title_h = 0;       // the title's lines and the gap under them
  bool stacked = false;  // the table's labels set above their text
};

class Flower {
 public:
  Flower(const CardFonts& f, int width, int margin) : f_(f), margin_(margin), right_(width - margin) {}

  Flow flow(const Card& card, bool title_big, bool rows_big) {
    Flow out;
    for (const std::string& l : wrap(f_, title_big, card.title, right_ - margin_))
      push(out, -1, {{title_big, l, margin_, CardRole::kTitle}}, pitch_of(f_, title_big));
    y_ += pitch_of(f_, false) / 2;
    out.title_h = y_;
    big_ = rows_big;
    const std::vector<int> col_w = columns(card.rows, 0);
    out.stacked = !columns_fit(card.rows, col_w, margin_);
    const std::vector<int> rest_w = columns(card.rows, 1);
    for (size_t r = 0; r < card.rows.size(); ++r) {
      const std::vector<std::string>& row = card.rows[r];
      if (row.size() <= 1 || !out.stacked) {
        table_row(out, static_cast<int>(r), row, 0, col_w, margin_);
        continue;
      }
      if (!row[0].empty()) push(out, static_cast<int>(r), {{big_, row[0], margin_, CardRole::kLabel}}, pitch_of(f_, big_));
      table_row(out, static_cast<int>(r), row, 1, rest_w, margin_ + indent());
    }
    return out;
  }

 private:
  int indent() const { return 2 * std::max(1, f_.normal_w[static_cast<size_t>('0')]); }

  void push(Flow& out, int row, std::vector<CardText> texts, int height) {
    out.lines.push_back(CardLine{std::move(texts), y_, height});
    out.row.push_back(row);
    y_ += height;
  }

  // Widths of the table columns from cell `from` on (each its widest cell + 2 digits; last cells excepted).
  std::vector<int> columns(const std::vector<std::vector<std::string>>& rows, size_t from) const {
    std::vector<int> w;
    for (const auto& row : rows)
      for (size_t c = from; c + 1 < row.size(); ++c) {
        if (w.size() <= c - from) w.resize(c - from + 1, 0);
        w[c - from] = std::max(w[c - from], card_text_px(f_, big_, row[c]) + indent());
      }
    return w;
  }

  // The columns fit when every table row's last cell fits whole beside them
  // or keeps two fifths of the width to wrap in.
  bool columns_fit(const std::vector<std::vector<std::string>>& rows, const std::vector<int>& col_w, int x0) const {
    for (const auto& row : rows) {
      if (row.size() <= 1) continue;
      int x = x0;
      for (size_t c = 0; c + 1 < row.size(); ++c) x += col_w[c];
      const int room = right_ - x;
      if (room < std::min(card_text_px(f_, big_, row.back()), 2 * (right_ - margin_) / 5)) return false;
    }
    return true;
  }

  // A row's cells from `from` on in columns from x0, its last cell wrapped at the right margin.
  void table_row(Flow& out, int r, const std::vector<std::string>& row, size_t from, const std::vector<int>& col_w,
                 int x0) {
    std::vector<CardText> first;
    int x = x0;
    for (size_t c = from; c + 1 < row.size(); ++c) {
      first.push_back({big_, row[c], x, c == 0 ? CardRole::kLabel : CardRole::kText});
      x += col_w[c - from];
    }
    const std::string last = row.size() > from ? row.back() : std::string();
    for (const std::string& l : wrap(f_, big_, last, std::max(1, right_ - x))) {
      first.push_back({big_, l, x, CardRole::kText});
      push(out, r, std::move(first), pitch_of(f_, big_));
      first.clear();
    }
  }

  const CardFonts& f_;
  int margin_, right_;
  int y_ = 0;
  bool big_ = false;
};

// Greedy pages of a flow: a row's lines kept on one page when they fit one,
// a blank line not at a page's top; each page under the title (repeated)
// when the title and a line fit, else the title is the first page's lines.
std::vector<CardPage> paginate(const Flow& flow, int avail, int mark_h) {
  const int line_max = [&] {
    int m = 0;
    for (size_t i = 0; i < flow.lines.size(); ++i)
      if (flow.row[i] >= 0) m = std::max(m, flow.lines[i].height);
    return m;
  }();
  const bool repeat_title = flow.title_h + line_max + mark_h <= avail;
  const int body_avail = avail - mark_h - (repeat_title ? flow.title_h : 0);
  std::vector<std::vector<size_t>> pages(1);
  int used = 0;
  for (size_t i = 0; i < flow.lines.size(); ++i) {
    if (repeat_title && flow.row[i] < 0) continue;
    const int h = flow.lines[i].height;
    int group = 0;  // height of this line's row from here on
    for (size_t j = i; j < flow.lines.size() && flow.row[j] == flow.row[i]; ++j) group += flow.lines[j].height;
    const bool row_start = i == 0 || flow.row[i - 1] != flow.row[i];
    const bool blank = flow.lines[i].texts.empty() || (flow.lines[i].texts.size() == 1 && flow.lines[i].texts[0].text.empty());
    if (used > 0 && (used + h > body_avail || (row_start && used + group > body_avail && group <= body_avail)))
      pages.emplace_back(), used = 0;
    if (used == 0 && blank && pages.size() > 1) continue;
    pages.back().push_back(i);
    used += h;
  }
  std::vector<CardPage> out;
  for (const auto& p : pages) {
    CardPage page;
    if (repeat_title)
      for (size_t i = 0; i < flow.lines.size() && flow.row[i] < 0; ++i) page.lines.push_back(flow.lines[i]);
    int top = repeat_title ? flow.title_h : 0;
    for (const size_t i : p) {
      page.lines.push_back(flow.lines[i]);
      page.lines.back().top = top;
      top += flow.lines[i].height;
    }
    out.push_back(std::move(page));
  }
  return out;
}

}  // namespace

int card_text_px(const CardFonts& fonts, bool big, const std::string& t) {
  int w = 0, best = 0;
  for (const char c : t) {
    if (c == '\n') w = 0;
    else best = std::max(best, w += char_px(fonts, big, c));
  }
  return best;
}

std::vector<CardPage> lay_out_card(const Card& card, const CardFonts& fonts, int width, int height) {
  const int pad = std::max(2, std::max(1, fonts.normal_w[static_cast<size_t>('0')]) / 2);
  const int margin = std::max(2 * pad, width / 24);
  const int avail = height - 2 * margin;
  // The largest fonts in which the card fits one page: rows big (a large
  // card, its table in columns), the title big, or neither; else pages.
  std::vector<CardPage> pages;
  for (const auto& [title_big, rows_big] : {std::pair{true, true}, {true, false}, {false, false}}) {
    if (rows_big && !card.large) continue;
    const Flow flow = Flower(fonts, width, margin).flow(card, title_big, rows_big);
    const int h = flow.lines.empty() ? 0 : flow.lines.back().top + flow.lines.back().height;
    if (h <= avail && !(rows_big && flow.stacked)) {
      pages = paginate(flow, avail, 0);
      break;
    }
  }
  if (pages.empty()) {
    const int mark_h = pitch_of(fonts, false);
    pages = paginate(Flower(fonts, width, margin).flow(card, false, false), avail, mark_h);
    for (size_t k = 0; k < pages.size() && pages.size() > 1; ++k) {
      const std::string mark = fmt::format("{}/{}", k + 1, pages.size());
      pages[k].lines.push_back(CardLine{
          {{false, mark, width - margin - card_text_px(fonts, false, mark), CardRole::kPageMark}}, avail - mark_h, mark_h});
    }
  }
  for (CardPage& p : pages)
    for (CardLine& l : p.lines) l.top += margin;
  return pages;
}

}  // namespace gpm::render
