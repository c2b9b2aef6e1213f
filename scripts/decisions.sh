#!/usr/bin/env bash
# Prints the list of every `DECISION:` note in src/ for ARCHITECTURE.md ("Every `DECISION:` in
# the code"): by file, each note's first sentence (its comment lines joined), cut at a word
# boundary within 177 bytes (the width the list had when it was kept by hand).
#
# Usage:
#   scripts/decisions.sh           # print the list
#   scripts/decisions.sh --write   # replace the list in ARCHITECTURE.md with it
#   scripts/decisions.sh --check   # exit 1 (and show the difference) when ARCHITECTURE.md's differs
# The list in ARCHITECTURE.md is the block of "- `src/…`" and "  - …" lines after the heading.
set -euo pipefail
cd "$(dirname "$0")/.."

architecture=ARCHITECTURE.md
heading='## Every `DECISION:` in the code'

# The list, from the notes in src/.
decisions() {
    # Files by path, so that the list's order does not depend on the file system.
    grep -rl "DECISION:" src | LC_ALL=C sort | while read -r file; do
        # Bytes, not characters, whatever the awk and the locale: the same cut everywhere.
        LC_ALL=C awk -v file="$file" -v max_bytes=177 '
            # A comment line: its text without the comment marker; anything else ends a note.
            function comment_text(line) {
                if (match(line, /^[ \t]*\/\/[\/!]?[ \t]?/)) return substr(line, RLENGTH + 1)
                return ""
            }
            function is_comment(line) { return line ~ /^[ \t]*\/\// }
            function flush() {
                if (note == "") return
                # The first sentence: up to a full stop followed by a space and no digit (not "0.4").
                if (match(note, /\. [^0-9]/)) note = substr(note, 1, RSTART)
                if (length(note) > max_bytes) {
                    # A character cut in two is part of the last word, which goes.
                    cut = substr(note, 1, max_bytes)
                    sub(/ [^ ]*$/, "", cut)
                    note = cut " …"
                }
                if (!header) { print "- `" file "`"; header = 1 }
                print "  - " note
                note = ""
            }
            {
                if (collecting && is_comment($0) && $0 !~ /DECISION:/) {
                    text = comment_text($0)
                    if (text == "") { flush(); collecting = 0 } else note = note " " text
                    next
                }
                if (collecting) { flush(); collecting = 0 }
                # A note, not a mention of the marker in backticks.
                if (is_comment($0) && $0 ~ /DECISION: / && $0 !~ /`DECISION:`/) {
                    text = comment_text($0)
                    sub(/^.*DECISION: /, "", text)
                    note = text
                    collecting = 1
                }
            }
            END { flush() }
        ' "$file"
    done
}

# ARCHITECTURE.md with its list replaced by the file named in $1.
with_list() {
    awk -v heading="$heading" -v list="$1" '
        $0 == heading { in_section = 1 }
        in_section && /^(- `|  - )/ {
            if (!replaced) { while ((getline line < list) > 0) print line; replaced = 1 }
            next
        }
        in_section && replaced { in_section = 0 }
        { print }
    ' "$architecture"
}

case "${1:-}" in
    "")
        decisions
        ;;
    --write | --check)
        list="$(mktemp)"
        updated="$(mktemp)"
        trap 'rm -f "$list" "$updated"' EXIT
        decisions >"$list"
        with_list "$list" >"$updated"
        if [[ "$1" == --write ]]; then
            cp "$updated" "$architecture"
        elif ! diff -u "$architecture" "$updated"; then
            echo "$architecture: the DECISION list is out of date; run scripts/decisions.sh --write" >&2
            exit 1
        fi
        ;;
    *)
        echo "usage: scripts/decisions.sh [--write | --check]" >&2
        exit 2
        ;;
esac
