#!/usr/bin/env bash
# Runs set-up's APT source detection (scripts/lib/apt-sources.sh, the code scripts/setup.sh uses)
# against temporary APT roots: a one-line sources.list only (a debootstrap minbase Debian 12), a
# deb822 debian.sources only (installer and container images), both, neither, and roots that
# already have a deb-src entry. Never runs apt. Prints one line per failed check; exits 1 if any.
set -Eeuo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
# shellcheck source=SCRIPTDIR/../../scripts/lib/apt-sources.sh
source "$here/../../scripts/lib/apt-sources.sh"

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
failures=0
fail() { printf 'FAIL [%s]: %s\n' "$case_name" "$*"; failures=$((failures + 1)); }

# new_root NAME: an empty APT root with an empty sources.list.d/, as debootstrap leaves it.
new_root() {
  case_name=$1
  root="$tmp/$1"
  mkdir -p "$root/sources.list.d"
}

# expect_plan FILE CONTENT: the planned deb-src entry is FILE (relative to the root) with CONTENT.
expect_plan() {
  local want_file=$1 want_content=$2 plan status=0
  plan=$(qv_apt_plan_deb_src "$root" 2>&1) || status=$?
  if [ "$status" -ne 0 ]; then
    fail "planning failed with status $status: $plan"
    return
  fi
  local file=${plan%%$'\n'*} content=${plan#*$'\n'}
  [ "$file" = "$root/$want_file" ] || fail "file '$file', expected '$root/$want_file'"
  [ "$content" = "$want_content" ] || fail "content:
$content
expected:
$want_content"
}

debian_sources='Types: deb
URIs: http://deb.debian.org/debian
Suites: bookworm bookworm-updates
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg

Types: deb
URIs: http://deb.debian.org/debian-security
Suites: bookworm-security
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg'

# 1. debootstrap minbase: only the one-line sources.list (the case of issue 21 item 0).
new_root oneline-only
echo 'deb http://deb.debian.org/debian bookworm main' >"$root/sources.list"
qv_apt_has_deb_src "$root" && fail "reports a deb-src entry where there is none"
expect_plan sources.list.d/quakeview-deb-src.list 'deb-src http://deb.debian.org/debian bookworm main'

# 2. One-line entries with options, comments and other suites: the bookworm main entry is mirrored
#    with its options (signed-by), the security and updates suites are not taken.
new_root oneline-options
cat >"$root/sources.list" <<'LIST'
# deb-src http://deb.debian.org/debian bookworm main
deb http://security.debian.org/debian-security bookworm-security main
deb [arch=amd64 signed-by=/usr/share/keyrings/debian-archive-keyring.gpg] http://ftp.de.debian.org/debian bookworm main contrib
LIST
qv_apt_has_deb_src "$root" && fail "a commented-out deb-src line counts as an entry"
expect_plan sources.list.d/quakeview-deb-src.list \
  'deb-src [arch=amd64 signed-by=/usr/share/keyrings/debian-archive-keyring.gpg] http://ftp.de.debian.org/debian bookworm main'

# 3. Only a deb822 debian.sources (Debian 12's installer and images): URIs and Signed-By kept.
new_root deb822-only
printf '%s\n' "$debian_sources" >"$root/sources.list.d/debian.sources"
qv_apt_has_deb_src "$root" && fail "reports a deb-src entry where there is none"
expect_plan sources.list.d/quakeview-deb-src.sources 'Types: deb-src
URIs: http://deb.debian.org/debian
Suites: bookworm
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg'

# 4. Both formats (a deb822 file plus a one-line sources.list): either gives a valid plan; the
#    one-line file is read first.
new_root both
echo 'deb http://deb.debian.org/debian bookworm main' >"$root/sources.list"
printf '%s\n' "$debian_sources" >"$root/sources.list.d/debian.sources"
qv_apt_has_deb_src "$root" && fail "reports a deb-src entry where there is none"
expect_plan sources.list.d/quakeview-deb-src.list 'deb-src http://deb.debian.org/debian bookworm main'

# 5. Neither (no sources.list, empty sources.list.d/, or only the security suite): fails and says
#    what to add.
for variant in none security-only; do
  new_root "$variant"
  [ "$variant" = none ] || echo 'deb http://security.debian.org/debian-security bookworm-security main' >"$root/sources.list"
  status=0
  message=$(qv_apt_plan_deb_src "$root" 2>&1 >/dev/null) || status=$?
  [ "$status" -ne 0 ] || fail "planning succeeded without any bookworm main source"
  case $message in
    *"deb http://deb.debian.org/debian bookworm main"*"$root/sources.list"*) ;;
    *) fail "the message does not say what to add: '$message'" ;;
  esac
done
new_root missing-root
rmdir "$root/sources.list.d" "$root"
status=0
qv_apt_plan_deb_src "$root" >/dev/null 2>&1 || status=$?
[ "$status" -ne 0 ] || fail "planning succeeded on a missing APT root"

# 6. Already has deb-src, in either format: detected, so set-up adds nothing.
new_root has-oneline-deb-src
printf 'deb http://deb.debian.org/debian bookworm main\ndeb-src http://deb.debian.org/debian bookworm main\n' \
  >"$root/sources.list"
qv_apt_has_deb_src "$root" || fail "misses the one-line deb-src entry"
new_root has-deb822-deb-src
printf '%s\n' "${debian_sources/Types: deb/Types: deb deb-src}" >"$root/sources.list.d/debian.sources"
qv_apt_has_deb_src "$root" || fail "misses the deb822 'Types: deb deb-src' entry"
new_root has-deb-src-in-list-d
echo 'deb http://deb.debian.org/debian bookworm main' >"$root/sources.list"
echo 'deb-src http://deb.debian.org/debian bookworm main' >"$root/sources.list.d/src.list"
qv_apt_has_deb_src "$root" || fail "misses a deb-src entry in sources.list.d/*.list"
new_root deb-src-disabled
printf 'Types: deb deb-src\nEnabled: no\nURIs: http://deb.debian.org/debian\nSuites: bookworm\nComponents: main\n' \
  >"$root/sources.list.d/debian.sources"
qv_apt_has_deb_src "$root" && fail "a stanza with 'Enabled: no' counts as an entry"

# 7. setup.sh itself: it sources this library and reports any failure with its reason (an ERR
#    trap), never exiting silently. Checked on its text, since running it would call apt.
setup="$here/../../scripts/setup.sh"
# shellcheck disable=SC2016 # the literal text of setup.sh
grep -q 'source "$root/scripts/lib/apt-sources.sh"' "$setup" || fail "setup.sh does not use the library"
grep -q "trap 'on_error" "$setup" || fail "setup.sh has no ERR trap"
grep -q 'sources.list.d/\*.list' "$setup" && fail "setup.sh globs sources.list.d/*.list itself"

case_name=summary
if [ "$failures" -gt 0 ]; then
  echo "$failures check(s) failed"
  exit 1
fi
echo "apt source detection: all checks passed"
