#!/usr/bin/env bash
# Fails, naming each file, when a C++ source in a folder listed in
# formatted_folders.txt is not as clang-format-14 and the repository's
# .clang-format leave it. Usage: check_format.sh SOURCE_ROOT
set -euo pipefail
root=${1:?usage: check_format.sh SOURCE_ROOT}
formatter=$(command -v clang-format-14 || true)
if [[ -z $formatter ]]; then
  echo "check_format: clang-format-14 is missing (deploy/install-deps.sh installs it)" >&2
  exit 1
fi
cd "$root"
folders=()
while read -r line; do
  [[ -z $line || $line == \#* ]] && continue
  folders+=("$line")
done < tests/format/formatted_folders.txt
checked=0
wrong=()
while IFS= read -r -d '' file; do
  checked=$((checked + 1))
  if ! "$formatter" --style=file --dry-run --Werror "$file" >/dev/null 2>&1; then wrong+=("$file"); fi
done < <(find "${folders[@]}" -type d -name node_modules -prune -o -type f \( -name '*.h' -o -name '*.cc' -o -name '*.cpp' \) -print0)
if ((checked == 0)); then
  echo "check_format: no C++ source found under ${folders[*]}" >&2
  exit 1
fi
if ((${#wrong[@]} > 0)); then
  echo "check_format: ${#wrong[@]} of $checked files are not formatted (run: clang-format-14 -i FILE):" >&2
  printf '  %s\n' "${wrong[@]}" >&2
  exit 1
fi
echo "check_format: $checked files under ${folders[*]} are formatted"
