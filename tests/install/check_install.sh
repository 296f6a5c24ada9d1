#!/usr/bin/env bash
# Installs the build into a folder and checks what it put there: the program runs, the man page
# and the completion are in place, the Python package imports from its install folder, and a
# program of a user's own builds against find_package(snapjump) and gets Zoelly's pressure.
# Usage: check_install.sh BUILD_DIR THIS_FOLDER WORK_DIR
set -euo pipefail
build=$1 here=$2 work=$3
rm -rf "$work"
cmake --install "$build" --prefix "$work/prefix" > "$work.log" 2>&1 || { cat "$work.log"; exit 1; }
prefix=$work/prefix
"$prefix/bin/snapjump" --version
test -s "$prefix/share/bash-completion/completions/snapjump"
if command -v help2man > /dev/null; then
  test -s "$prefix/share/man/man1/snapjump.1"
  grep -q "snapjump" "$prefix/share/man/man1/snapjump.1"
fi
test -s "$prefix/lib/cmake/snapjump/snapjumpConfig.cmake"
test -s "$prefix/include/snapjump/config/case.hpp"
py=$(find "$prefix" -path '*dist-packages/snapjump/__init__.py' | head -1)
if [ -n "$py" ]; then
  PYTHONPATH=$(dirname "$(dirname "$py")") /usr/bin/python3 -c \
    "import snapjump; print('python', snapjump.predict()['outcome_text'])"
fi
# The completion offers a subcommand's options.
out=$(bash -c "source '$prefix/share/bash-completion/completions/snapjump'; PATH='$prefix/bin':\$PATH; \
  COMP_WORDS=(snapjump run --reso); COMP_CWORD=2; _snapjump; echo \${COMPREPLY[*]}")
echo "completion: $out"
[[ " $out " == *" --resolution "* ]]
cmake -S "$here" -B "$work/user" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release \
  > "$work/user.log" 2>&1 || { cat "$work/user.log"; exit 1; }
cmake --build "$work/user" >> "$work/user.log" 2>&1 || { cat "$work/user.log"; exit 1; }
"$work/user/uses_snapjump"
