# bash completion for snapjump (installed as share/bash-completion/completions/snapjump): the
# subcommands, and each subcommand's options as its --help lists them.
_snapjump() {
  local cur=${COMP_WORDS[COMP_CWORD]}
  local subs="predict contact analyze mesh run sweep plot"
  if [ "$COMP_CWORD" -eq 1 ]; then
    mapfile -t COMPREPLY < <(compgen -W "$subs --help --version" -- "$cur")
    return
  fi
  local words=("${COMP_WORDS[1]}")
  if [ "${COMP_WORDS[1]}" = plot ]; then
    if [ "$COMP_CWORD" -eq 2 ]; then
      mapfile -t COMPREPLY < <(compgen -W "series sections sweep contact" -- "$cur")
      return
    fi
    words+=("${COMP_WORDS[2]}")
  fi
  if [[ $cur == -* ]]; then
    local options
    options=$("${COMP_WORDS[0]}" "${words[@]}" --help 2>/dev/null | grep -o -- '--[A-Za-z0-9-]*' | sort -u)
    mapfile -t COMPREPLY < <(compgen -W "$options" -- "$cur")
  else
    mapfile -t COMPREPLY < <(compgen -f -- "$cur")
  fi
}
complete -o filenames -F _snapjump snapjump
