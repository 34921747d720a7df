# shellcheck shell=bash
# Which of the machine's apt entries are Debian's own archive (sourced by tools/setup, which derives
# deb-src entries from them, and tools/fresh-check, which takes a pristine root's mirror from them). No
# archive host is named in the project: the machine's own entries are used, whatever mirror or
# snapshot it is pointed at. An entry counts as Debian when:
#   - it names a Signed-By key and that key is the Debian archive keyring (debian-archive-keyring*), or
#   - it names no Signed-By key and its URI path is exactly /debian or /debian-security (optionally a
#     snapshot form .../archive/debian[-security]/<timestamp>), the layout of Debian's archive and its
#     mirrors. A third-party path such as /linux/debian does not match.
# Anything else (nodesource, cloud SDKs, docker, ...) is not Debian's: third-party repositories often
# publish no source indices, and a deb-src entry for one makes 'apt-get update' fail or warn.
#
# For awk (-v re="$DEBIAN_URI_RE" -v keyring="$DEBIAN_KEYRING"): a one-line entry's options "[...]"
# match ("signed-by=[^] \t]*" keyring) when they name the keyring; a deb822 Signed-By value matches
# keyring; a URI without its trailing slashes matches re.
DEBIAN_URI_RE='^[a-z+]+://[^/]+(/archive)?/debian(-security)?(/[0-9]{8}T[0-9]{6}Z)?/?$'
DEBIAN_KEYRING='debian-archive-keyring'
