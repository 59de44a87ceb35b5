#!/bin/sh
# Fetch and unpack what sources.txt pins, through apt, into DIR:
#   DIR/download/  the files as fetched (kept: a rerun fetches nothing)
#   DIR/src/NAME/  each source package unpacked with Debian's patches;
#                  each binary package's files
# apt runs with a state of its own under DIR/apt (the machine's archives,
# their deb-src side added), so the machine's own apt setup is left as it is.
# A file whose sha256 differs from the pin stops everything.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
dir=$(mkdir -p "$1" && cd "$1" && pwd)
apt="$dir/apt"
mkdir -p "$apt/lists/partial" "$apt/cache/archives/partial" "$apt/sources" "$dir/download" "$dir/src"

# The machine's Debian archives, for binary and source packages alike.
for f in /etc/apt/sources.list /etc/apt/sources.list.d/*.sources /etc/apt/sources.list.d/*.list; do
    [ -f "$f" ] || continue
    case "$f" in
        *.sources) sed 's/^Types:.*/Types: deb deb-src/' "$f" ;;
        *) sed -n 's/^deb \(.*\)/deb \1\ndeb-src \1/p' "$f" ;;
    esac >"$apt/sources/$(basename "$f" | tr '/' '_')"
done
opts="-o Dir::Etc::SourceList=/dev/null -o Dir::Etc::SourceParts=$apt/sources -o Dir::State::Lists=$apt/lists
      -o Dir::Cache=$apt/cache -o APT::Sandbox::User=root -q"

check() { # FILE SHA256
    echo "$2  $1" | sha256sum -c --quiet - || { echo "fetch_sources: $1 is not the pinned file" >&2; exit 1; }
}

updated=no
update() {
    [ "$updated" = yes ] && return
    # shellcheck disable=SC2086
    apt-get $opts update >"$apt/update.log" 2>&1 || { cat "$apt/update.log" >&2; exit 1; }
    updated=yes
}

grep -v '^#' "$here/sources.txt" | while read -r kind name version sha; do
    [ -n "$kind" ] || continue
    bare=${version#*:}          # the epoch is not part of a file name
    cd "$dir/download"
    case "$kind" in
        src)
            dsc="${name}_${bare}.dsc"
            if [ ! -f "$dsc" ]; then
                update
                # shellcheck disable=SC2086
                apt-get $opts source --download-only "$name=$version" >"$apt/$name.log" 2>&1 ||
                    { cat "$apt/$name.log" >&2; exit 1; }
            fi
            check "$dsc" "$sha"
            if [ ! -d "$dir/src/$name" ]; then
                rm -rf "$dir/src/$name.tmp"
                dpkg-source --require-strong-checksums -x "$dsc" "$dir/src/$name.tmp" >"$apt/$name.unpack.log" 2>&1 ||
                    { cat "$apt/$name.unpack.log" >&2; exit 1; }
                mv "$dir/src/$name.tmp" "$dir/src/$name"
            fi ;;
        deb)
            deb="${name}_${bare}_amd64.deb"
            if [ ! -f "$deb" ]; then
                update
                # shellcheck disable=SC2086
                apt-get $opts download "$name=$version" >"$apt/$name.log" 2>&1 ||
                    { cat "$apt/$name.log" >&2; exit 1; }
            fi
            check "$deb" "$sha"
            if [ ! -d "$dir/src/$name" ]; then
                dpkg-deb -x "$deb" "$dir/src/$name.tmp" && mv "$dir/src/$name.tmp" "$dir/src/$name"
            fi ;;
        *) echo "fetch_sources: unknown kind $kind" >&2; exit 1 ;;
    esac
    echo "fetch_sources: $name $version"
done
