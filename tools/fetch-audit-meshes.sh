#!/usr/bin/env bash
# Fetches the real meshes of the README's spawn-audit tables into BUILD/audit-meshes (default build/): the
# Stanford bunny, Keenan Crane's Spot, Hoppe's fandisk and the Utah teapot, from Alec Jacobson's
# common-3d-test-models at a pinned commit, each checked against its SHA-256. They are not in the repository
# (their licences are their authors'); tools/docs.py regenerates the tables and the picture when they are there.
#
#   tools/fetch-audit-meshes.sh [BUILD]          download (curl) from raw.githubusercontent.com
#   tools/fetch-audit-meshes.sh [BUILD] --git DIR   take them from a clone of the repository instead
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
source_git=
if [ "${2:-}" = "--git" ]; then source_git=${3:?"--git needs a directory"}; fi
commit=8a4f8642acaf43f9cd7b67858a1502e1055ef202
out="$build/audit-meshes"
mkdir -p "$out"
while read -r sha name; do
  if [ -n "$source_git" ]; then
    git -C "$source_git" show "$commit:data/$name" > "$out/$name.part"
  else
    curl -fsSL "https://raw.githubusercontent.com/alecjacobson/common-3d-test-models/$commit/data/$name" -o "$out/$name.part"
  fi
  echo "$sha  $out/$name.part" | sha256sum -c --quiet - || { echo "fetch-audit-meshes: $name: checksum mismatch" >&2; exit 1; }
  mv "$out/$name.part" "$out/$name"
  echo "fetch-audit-meshes: $out/$name"
done <<'LIST'
1eb35d1e21ce99e5ce911353b6be278990713448dd9e8f5c9387f9de39b32205 stanford-bunny.obj
0738b5e8608fed74e5e8c7aa8dd0af97b4b74f9f6cbf7aac84cd7e40b2e44a75 spot.obj
ea5bab2fbf545b1915f0d9faf6cc61ff8c18e0d8174ad61f8e35de15d8f6e3f8 fandisk.obj
1b5396fedd74b577e32cef41146582c2f2e1a050d5b4915193c0ac1ad4187ed4 teapot.obj
LIST
