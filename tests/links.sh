#!/usr/bin/env bash
# links.sh: every relative link in README.md and docs/*.md leads to a file of the repository, and every #anchor to a heading of its page (GitHub's heading ids).
#
# Prints one line per broken link (FILE:LINE: LINK: what is wrong) and exits 1 if there is any;
# prints `links: N relative links checked` and exits 0 otherwise. Web links (scheme:) are not
# checked.
set -u
cd "$(dirname "$0")/.."

# The ids GitHub gives the headings of markdown file $1, one per line: lowercase, characters
# other than letters, digits, spaces, '-' and '_' dropped, spaces turned into '-'; a repeated
# id gets -1, -2, ...
anchors() {
  grep -E '^#{1,6} ' "$1" | sed -E 's/^#+ +//; s/ +#* *$//' |
    sed -E 's/`//g; s/\[([^]]*)\]\([^)]*\)/\1/g' | tr '[:upper:]' '[:lower:]' |
    sed -E 's/[^a-z0-9 _-]//g; s/ /-/g' |
    awk '{ n = seen[$0]++; print (n ? $0 "-" n : $0) }'
}

bad=0 n=0
for f in README.md docs/*.md; do
  dir=$(dirname "$f")
  # [text](target) outside code spans: the target up to ')' or a space (a title)
  while IFS=: read -r line link; do
    case "$link" in *://*|mailto:*) continue ;; esac
    n=$((n + 1))
    path=${link%%#*} anchor=
    [[ $link == *#* ]] && anchor=${link#*#}
    target=$f
    if [ -n "$path" ]; then
      target=$dir/$path
      if [ ! -e "$target" ]; then
        echo "$f:$line: $link: no such file ($target)"
        bad=1
        continue
      fi
    fi
    if [ -n "$anchor" ]; then
      if [[ $target != *.md ]] || ! anchors "$target" | grep -qxF -- "$anchor"; then
        echo "$f:$line: $link: no heading with that anchor in $target"
        bad=1
      fi
    fi
  done < <(sed 's/`[^`]*`//g' "$f" | grep -noE '\]\([^) ]+' | sed -E 's/\]\(//')
done
[ "$bad" -eq 0 ] && echo "links: $n relative links checked in README.md and docs/*.md"
exit "$bad"
