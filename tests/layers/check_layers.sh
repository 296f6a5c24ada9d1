#!/usr/bin/env bash
# The build's layer views (CMakeLists.txt, "The library in layers") keep a layer from including
# the layers above it. Compiles one include a layer may make, which must compile, and for every
# layer each layer it may not use, which must fail for want of the header.
#   check_layers.sh CXX BUILD_DIR SOURCE_DIR
set -u
export LC_ALL=C  # the compiler's messages in English
cxx=$1 build=$2 src=$3
fail=0
probe=$(mktemp -d)
trap 'rm -rf "$probe"' EXIT
# A layer that includes what it may: the finite elements use the mesh.
echo '#include "mesh/mesh.hpp"' >"$probe/ok.cpp"
if ! "$cxx" -std=c++20 -fsyntax-only -I"$build/layers/fem" "$probe/ok.cpp" 2>"$probe/ok.log"; then
  echo "fem cannot include mesh/mesh.hpp:"; cat "$probe/ok.log"; fail=1
fi
checked=0
for view in "$build"/layers/*/; do
  layer=$(basename "$view")
  for other in "$src"/src/*/; do
    o=$(basename "$other")
    [ -e "$view/$o" ] && continue
    header=$(cd "$other" && ls *.hpp 2>/dev/null | head -1)
    [ -n "$header" ] || continue
    echo "#include \"$o/$header\"" >"$probe/bad.cpp"
    if "$cxx" -std=c++20 -fsyntax-only -I"$view" "$probe/bad.cpp" 2>"$probe/bad.log"; then
      echo "layer $layer can include $o/$header, which its view should not hold"; fail=1
    elif ! grep -q "No such file" "$probe/bad.log"; then
      echo "layer $layer including $o/$header failed for another reason:"; cat "$probe/bad.log"; fail=1
    fi
    checked=$((checked + 1))
  done
done
[ "$checked" -gt 50 ] || { echo "only $checked forbidden includes checked: are the views built?"; fail=1; }
# And every library source is compiled against its layer's view, never against the whole src/.
if [ -f "$build/compile_commands.json" ]; then
  bad=$(awk -v src="$src/src" '
    /"command":/ { cmd = $0 }
    /"file":/ {
      if (index($0, "\"" src "/") > 0 && (index(cmd, "-I" src " ") > 0 || index(cmd, "-I" src "\"") > 0)) print $0
    }' "$build/compile_commands.json")
  if [ -n "$bad" ]; then
    echo "compiled against the whole src/ instead of a layer's view:"; echo "$bad"; fail=1
  fi
  views=$(grep -c -- "-I[^ ]*/layers/" "$build/compile_commands.json")
  [ "$views" -gt 20 ] || { echo "only $views compile lines use a layer's view"; fail=1; }
fi
echo "$checked forbidden includes refused"
exit $fail
