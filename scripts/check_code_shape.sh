#!/usr/bin/env bash
# Checks the code's shape: no production function over 80 lines, no header
# with more than 40 lines of comment before its first declaration, a README
# front page of at most 200 lines. Prints each violation on one line and exits
# 1 when there is any (0 and one summary line otherwise).
#   bash scripts/check_code_shape.sh [ROOT]     (default: this repository)
set -euo pipefail
root=${1:-"$(dirname "$0")/.."}
cd "$root"
max_function=80 max_header_comment=40 max_readme=200
present=()
for d in app calib sim hw run report models render python; do [[ -d $d ]] && present+=("$d"); done
command -v ctags >/dev/null || { echo "check_code_shape: ctags not found (Debian package universal-ctags; scripts/setup.sh installs it)" >&2; exit 2; }
violations=() functions=0 headers=0
# Function definitions with their first and last line (universal-ctags).
while read -r end start name file; do
  functions=$((functions + 1))
  len=$((end - start + 1))
  ((len > max_function)) && violations+=("$file: function $name is $len lines (at most $max_function)")
done < <(ctags -R --languages=C++ --kinds-C++=f --fields=+ne -x --_xformat="%{end} %n %N %F" "${present[@]}" |
         awk 'NF == 4 && $1 ~ /^[0-9]+$/')
# Comment lines before the first line that is neither comment, blank nor preprocessor.
while IFS= read -r -d '' h; do
  headers=$((headers + 1))
  n=$(awk '/^[[:space:]]*\/\//{c++; next} /^[[:space:]]*$/ || /^#/ {next} {exit} END{print c + 0}' "$h")
  ((n > max_header_comment)) && violations+=("$h: $n comment lines before the first declaration (at most $max_header_comment)")
done < <(find "${present[@]}" -name '*.hpp' -print0)
readme=$(wc -l < README.md)
((readme > max_readme)) && violations+=("README.md: $readme lines (at most $max_readme)")
if ((${#violations[@]})); then
  printf '%s\n' "${violations[@]}"
  exit 1
fi
echo "code shape: $functions functions of at most $max_function lines, $headers headers with at most $max_header_comment comment lines first, README $readme lines"
