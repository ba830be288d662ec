#!/usr/bin/env bash
# Checks or applies the repository's C++ formatting (.clang-format at the top) with clang-format.
#   scripts/format.sh --check   list every tracked .cpp/.hpp that clang-format would change; exit 1
#                               if there is one, 0 if none (the ctest entry `format` runs this)
#   scripts/format.sh --fix     rewrite those files in place
# Files: the C++ sources git tracks (git ls-files), so build trees and untracked scratch files are
# never touched. CLANG_FORMAT overrides the binary (default: clang-format-14, Debian 12's, else
# clang-format). Exit 2 on usage errors or when clang-format or git is missing.
set -euo pipefail

usage() { echo "usage: scripts/format.sh --check | --fix" >&2; exit 2; }
[ $# -eq 1 ] || usage
case "$1" in
  --check|--fix) mode="$1" ;;
  *) usage ;;
esac

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"

tool="${CLANG_FORMAT:-}"
if [ -z "$tool" ]; then
  for candidate in clang-format-14 clang-format; do
    if command -v "$candidate" >/dev/null 2>&1; then tool="$candidate"; break; fi
  done
fi
if [ -z "$tool" ] || ! command -v "$tool" >/dev/null 2>&1; then
  echo "format.sh: clang-format not found (install clang-format-14, scripts/deps.sh)" >&2
  exit 2
fi
if ! git -C "$root" rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  echo "format.sh: $root is not a git work tree; the file list comes from git ls-files" >&2
  exit 2
fi
[ -f "$root/.clang-format" ] || { echo "format.sh: $root/.clang-format is missing" >&2; exit 2; }

mapfile -d '' files < <(git ls-files -z -- '*.cpp' '*.hpp' '*.h' '*.cc')
if [ ${#files[@]} -eq 0 ]; then
  echo "format.sh: no tracked C++ files" >&2
  exit 2
fi

if [ "$mode" = "--fix" ]; then
  "$tool" -i --style=file -- "${files[@]}"
  echo "format.sh: formatted ${#files[@]} files with $tool"
  exit 0
fi

# One call for every file (a call per file costs ten times as long); each file that would change
# is named in its "code should be clang-formatted" warnings.
rc=0
out="$("$tool" --dry-run --Werror --style=file -- "${files[@]}" 2>&1)" || rc=$?
mapfile -t bad < <(printf '%s\n' "$out" |
  sed -n 's/^\(.*\):[0-9]*:[0-9]*: error: code should be clang-formatted.*/\1/p' | sort -u)
if [ $rc -ne 0 ] && [ ${#bad[@]} -eq 0 ]; then
  printf '%s\n' "$out" >&2
  echo "format.sh: $tool failed without naming a file to format" >&2
  exit 2
fi
# Any other error (a file clang-format could not read) is shown too.
printf '%s\n' "$out" | grep ': error: ' | grep -v 'code should be clang-formatted' >&2 || true
if [ ${#bad[@]} -gt 0 ]; then
  printf '%s\n' "${bad[@]}"
  echo "format.sh: ${#bad[@]} of ${#files[@]} files need formatting ($tool); run scripts/format.sh --fix" >&2
  exit 1
fi
echo "format.sh: all ${#files[@]} files formatted ($tool)"
