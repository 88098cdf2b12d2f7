#!/usr/bin/env bash
# Man pages and bash completion made from the text `lucent --help` and `lucent CMD --help` print, so
# the three cannot drift apart (issue 35). Run by the build (cmake/install.cmake) with the built
# command; writes OUT/man/lucent.1, OUT/man/lucent-CMD.1 per command and OUT/completion/lucent.
# Usage: docs_from_help.sh LUCENT OUT VERSION
set -euo pipefail
lucent=$1 out=$2 version=$3
mkdir -p "$out/man" "$out/completion"

# The commands and their one-line summaries: the "commands:" block of `lucent --help`.
summaries=$("$lucent" --help | awk '/^commands:/ {on = 1; next} on && /^$/ {exit} on {print}')
commands=$(awk '{print $1}' <<<"$summaries")

# Text as roff: backslashes escaped, minus signs as \-, a leading dot or quote neutralised.
roff_text() { sed -e 's/\\/\\e/g' -e 's/-/\\-/g' -e "s/^\\([.']\\)/\\\\\\&\\1/"; }

# page NAME SUMMARY HELPTEXT: a man page whose SYNOPSIS is the help's usage lines and whose
# DESCRIPTION is the rest of the help, as printed (preformatted).
page() {
  local name=$1 summary=$2 help=$3 upper
  upper=$(tr '[:lower:]' '[:upper:]' <<<"$name")
  {
    printf '.TH "%s" "1" "" "Lucent %s" "Lucent Manual"\n' "$upper" "$version"
    printf '.SH NAME\n%s \\- %s\n' "$(roff_text <<<"$name")" "$(roff_text <<<"$summary")"
    printf '.SH SYNOPSIS\n.nf\n'
    awk 'NR == 1 {sub(/^usage: /, ""); print; next} /^ / && !done {sub(/^       /, ""); print; next} {done = 1}' \
      <<<"$help" | roff_text
    printf '.fi\n.SH DESCRIPTION\n.nf\n'
    awk 'NR == 1 || (/^ / && !skip_done) {next} {skip_done = 1; print}' <<<"$help" | roff_text
    printf '.fi\n.SH "SEE ALSO"\n'
    if [ "$name" = lucent ]; then
      sed 's/^/.BR lucent\\-/; s/$/ (1)/' <<<"$commands"
    else
      printf '.BR lucent (1)\n'
    fi
  } >"$out/man/$name.1.tmp"
  mv "$out/man/$name.1.tmp" "$out/man/$name.1"
}

page lucent "rendering translucent materials: kernels, shaders, Monte Carlo, path-traced references" \
  "$("$lucent" --help | sed 1,2d)"
while read -r cmd summary; do
  page "lucent-$cmd" "$summary" "$("$lucent" "$cmd" --help)"
done <<<"$summaries"

# Bash completion: the commands, then each command's options (the "--x" words its help lists) and
# file names.
{
  printf '# bash completion for lucent %s, made from its --help (cmake/docs_from_help.sh)\n' "$version"
  printf '_lucent() {\n'
  printf '  local cur=${COMP_WORDS[COMP_CWORD]} cmd=${COMP_WORDS[1]} opts\n'
  printf '  if [ "$COMP_CWORD" -eq 1 ]; then\n'
  printf '    COMPREPLY=($(compgen -W "%s --help --version" -- "$cur")); return\n' "$(tr '\n' ' ' <<<"$commands" | sed 's/ $//')"
  printf '  fi\n  case $cmd in\n'
  for cmd in $commands; do
    opts=$("$lucent" "$cmd" --help | grep -o -- '--[a-z][a-z0-9-]*' | sort -u | tr '\n' ' ' | sed 's/ $//')
    printf '    %s) opts="%s" ;;\n' "$cmd" "$opts -q --quiet --threads --part"
  done
  printf '    *) opts="" ;;\n  esac\n'
  printf '  if [[ "$cur" == -* ]]; then COMPREPLY=($(compgen -W "$opts" -- "$cur")); return; fi\n'
  printf '  COMPREPLY=($(compgen -f -- "$cur"))\n'
  printf '}\ncomplete -o filenames -F _lucent lucent\n'
} >"$out/completion/lucent.tmp"
mv "$out/completion/lucent.tmp" "$out/completion/lucent"
