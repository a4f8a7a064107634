# shellcheck shell=bash
# APT source detection for scripts/setup.sh, sourced (not run). Every function takes the APT
# configuration directory as its first argument (default /etc/apt), so tests/scripts/
# test-apt-sources.sh runs the same code against temporary folders.
#
# Debian 12 systems list their sources in either or both formats:
#   - one-line: $root/sources.list and $root/sources.list.d/*.list
#     ("deb [options] URI SUITE COMPONENT...");
#   - deb822:   $root/sources.list.d/*.sources (stanzas of "Types:", "URIs:", "Suites:",
#     "Components:", "Signed-By:"), the format of Debian 12's installer and container images.
# A debootstrap minbase system has only the one-line sources.list and an empty sources.list.d/.
# The functions never fail on a missing file or an unmatched glob.

# The files of one format under $1 that exist, one per line.
qv_apt_oneline_files() {
  local root=${1:-/etc/apt} f
  for f in "$root/sources.list" "$root"/sources.list.d/*.list; do
    [ -f "$f" ] && printf '%s\n' "$f"
  done
  return 0
}

qv_apt_deb822_files() {
  local root=${1:-/etc/apt} f
  for f in "$root"/sources.list.d/*.sources; do
    [ -f "$f" ] && printf '%s\n' "$f"
  done
  return 0
}

# Prints the enabled entries of type $2 (deb or deb-src) for the suite "bookworm" (not
# bookworm-updates or -security) with the component "main", in a normalized one-line form:
#   FORMAT|URIS|SIGNED_BY|OPTIONS
# FORMAT is "oneline" or "deb822"; URIS is space separated; SIGNED_BY may be empty; OPTIONS is the
# bracketed option list of a one-line entry (with its brackets) or empty.
qv_apt_entries() {
  local root=${1:-/etc/apt} type=$2
  local -a oneline deb822
  mapfile -t oneline < <(qv_apt_oneline_files "$root")
  mapfile -t deb822 < <(qv_apt_deb822_files "$root")
  if [ "${#oneline[@]}" -gt 0 ]; then
    awk -v want="$type" '
      { sub(/#.*/, "") }
      $1 == want {
        opts = ""; i = 2
        if ($2 ~ /^\[/) {
          opts = $2; i = 3
          while (opts !~ /\]$/ && i <= NF) { opts = opts " " $i; i++ }
        }
        uri = $i; suite = $(i + 1); main = 0
        for (j = i + 2; j <= NF; j++) if ($j == "main") main = 1
        if (suite == "bookworm" && main) printf "oneline|%s||%s\n", uri, opts
      }' "${oneline[@]}"
  fi
  if [ "${#deb822[@]}" -gt 0 ]; then
    # Paragraph mode: one stanza a record; fields may not span lines except by leading blanks
    # (continuation lines, used for inline keys), which are skipped.
    awk -v want="$type" '
      function flush() {
        if (types_ok && suite_ok && main_ok && enabled) printf "deb822|%s|%s|\n", uris, signed
        types_ok = suite_ok = main_ok = 0; enabled = 1; uris = signed = ""
      }
      BEGIN { enabled = 1 }
      /^[[:space:]]*$/ { flush(); next }
      /^[[:space:]]*#/ { next }
      /^[[:space:]]/ { next }
      {
        key = $0; sub(/:.*/, "", key); key = tolower(key)
        value = $0; sub(/^[^:]*:[[:space:]]*/, "", value); sub(/[[:space:]]+$/, "", value)
        n = split(value, words, /[[:space:]]+/)
        if (key == "types") for (j = 1; j <= n; j++) { if (words[j] == want) types_ok = 1 }
        if (key == "suites") for (j = 1; j <= n; j++) { if (words[j] == "bookworm") suite_ok = 1 }
        if (key == "components") for (j = 1; j <= n; j++) { if (words[j] == "main") main_ok = 1 }
        if (key == "uris") uris = value
        if (key == "signed-by") signed = value
        if (key == "enabled" && tolower(value) == "no") enabled = 0
      }
      END { flush() }' "${deb822[@]}"
  fi
  return 0
}

# True when a deb-src entry for bookworm main is already configured under $1.
qv_apt_has_deb_src() {
  [ -n "$(qv_apt_entries "${1:-/etc/apt}" deb-src)" ]
}

# Plans the deb-src entry that mirrors the first binary entry for bookworm main under $1 (keeping
# its URI and Signed-By: apt rejects a pair that disagrees). On success prints the path of the file
# to create on the first line and its content after it, in the format of the binary entry. Without
# a binary entry prints to stderr what to add and returns 1.
qv_apt_plan_deb_src() {
  local root=${1:-/etc/apt} first format uris signed opts
  first=$(qv_apt_entries "$root" deb)
  first=${first%%$'\n'*}
  if [ -z "$first" ]; then
    cat >&2 <<MSG
no APT source for Debian 12 "bookworm" main in $root/sources.list or $root/sources.list.d/.
Add one, for example the line
  deb http://deb.debian.org/debian bookworm main
to $root/sources.list, then run set-up again.
MSG
    return 1
  fi
  IFS='|' read -r format uris signed opts <<<"$first"
  if [ "$format" = deb822 ]; then
    printf '%s\n' "$root/sources.list.d/quakeview-deb-src.sources"
    printf 'Types: deb-src\nURIs: %s\nSuites: bookworm\nComponents: main\n' "$uris"
    [ -z "$signed" ] || printf 'Signed-By: %s\n' "$signed"
  else
    printf '%s\n' "$root/sources.list.d/quakeview-deb-src.list"
    printf 'deb-src %s%s bookworm main\n' "${opts:+$opts }" "$uris"
  fi
}
