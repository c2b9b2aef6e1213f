#!/usr/bin/env bash
# Times crawltrace against the tracers a user would otherwise pick (potrace, vtracer, autotrace's
# centerline mode) on the benchmark's 4000×3000 page and its scan-like JPEG, and prints a markdown
# table of wall time and peak memory. Tools that are not installed are skipped.
#
# Usage: scripts/compare-tracers.sh [WORKDIR]     (RUNS=N sets the timed runs per row, default 5)
#
# Inputs come from `cargo run --release --example bench_pages`: samples/page-4000x3000.png when
# present (else a generated stand-in), the scan-like JPEG, and both as 1-bit PBM binarized and
# cleaned by crawltrace, since potrace reads only bitmaps; that binarization is not timed, as a
# potrace user would threshold once and then trace.
# Wall time: hyperfine's median when hyperfine is installed, else the median of RUNS runs timed in
# bash, every tool run once a round in turn (so load from other processes falls on all alike).
# Peak memory: the largest maximum resident set size GNU time (/usr/bin/time) saw.
set -euo pipefail

RUNS=${RUNS:-5}
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
work=${1:-$(mktemp -d -t compare-tracers.XXXXXX)}
mkdir -p "$work/out"

cd "$root"
cargo build --release --quiet --bin crawltrace --example bench_pages
target/release/examples/bench_pages "$work" 2>/dev/null
crawltrace="$root/target/release/crawltrace"

VTRACER=${VTRACER:-$(command -v vtracer || echo /opt/vtracer/bin/vtracer)}
have() { command -v "$1" >/dev/null 2>&1 || [[ -x "$1" ]]; }
GNU_TIME=/usr/bin/time
[[ -x $GNU_TIME ]] && $GNU_TIME -f %M true >/dev/null 2>&1 || GNU_TIME=

skipped=()
# One entry per measured row, by index: its table cells and its command (shell-quoted).
labels=() modes=() inputs=() rsses=() path_counts=() sizes=() commands=()

# measure LABEL MODE INPUT OUTPUT COMMAND...: runs COMMAND, which writes the SVG OUTPUT, once to
# check it, three times for its peak memory, and registers it for timing; `time_all` times every
# registered command afterwards.
measure() {
    local label=$1 mode=$2 input=$3 output=$4
    shift 4
    "$@" >/dev/null 2>&1 || { skipped+=("$label on $input: failed"); return; }
    local rss=0 m
    if [[ -n $GNU_TIME ]]; then
        for _ in 1 2 3; do
            m=$($GNU_TIME -f %M "$@" 2>&1 >/dev/null | tail -n 1)
            if ((m > rss)); then rss=$m; fi
        done
        rss=$(awk -v k="$rss" 'BEGIN { printf "%.0f", k / 1024 }')
    else
        rss="n/a"
    fi
    labels+=("$label") modes+=("$mode") inputs+=("$input") rsses+=("$rss")
    path_counts+=("$({ grep -o '<path' "$output" || true; } | wc -l)")
    sizes+=("$(($(wc -c <"$output") / 1024))")
    commands+=("$(printf '%q ' "$@")")
}

# Wall time of every registered command: hyperfine's median and σ when hyperfine is installed;
# else RUNS rounds in bash, each round running every command once in turn, so that load from
# other processes falls on all tools alike, and the median of each command's RUNS times.
walls=() sigmas=()
time_all() {
    local i
    if have hyperfine; then
        local csv="$work/hyperfine.csv"
        for i in "${!commands[@]}"; do
            # -N: no intermediate shell, so only the tracer is timed.
            hyperfine -N --warmup 1 --runs "$RUNS" --export-csv "$csv" -- "${commands[i]}" \
                >/dev/null 2>&1
            walls[i]=$(awk -F, 'NR == 2 { printf "%.3f", $4 }' "$csv")
            sigmas[i]=$(awk -F, 'NR == 2 { printf "%.3f", $3 }' "$csv")
        done
        return
    fi
    local times=() start end
    for _ in $(seq "$RUNS"); do
        for i in "${!commands[@]}"; do
            start=$(date +%s%N)
            eval "${commands[i]}" >/dev/null 2>&1 || true
            end=$(date +%s%N)
            times[i]+="$(((end - start) / 1000)) "
        done
    done
    for i in "${!commands[@]}"; do
        walls[i]=$(printf '%s\n' ${times[i]} | sort -n |
            awk '{ t[NR] = $1 } END { printf "%.3f", t[int((NR + 1) / 2)] / 1e6 }')
        sigmas[i]="–"
    done
}

load_before=$(cut -d' ' -f1-3 /proc/loadavg)

for input in page.png page-scan.jpg; do
    stem=${input%.*}
    measure "crawltrace $(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo)" \
        "centerline, decode → SVG file" "$input" "$work/out/$stem.crawltrace.svg" \
        "$crawltrace" trace -q "$work/$input" -o "$work/out/$stem.crawltrace.svg"
done

if have potrace; then
    for input in page.pbm page-scan.pbm; do
        stem=${input%.*}
        measure "potrace $(potrace --version | head -n 1 | awk '{ print $2 }' | sed 's/\.$//')" \
            "outline, PBM → SVG" "$input" "$work/out/$stem.potrace.svg" \
            potrace -s -o "$work/out/$stem.potrace.svg" "$work/$input"
    done
else
    skipped+=("potrace: not installed (Debian: apt-get install potrace)")
fi

if have "$VTRACER"; then
    for input in page.png page-scan.jpg; do
        stem=${input%.*}
        # Binary mode is `--colormode bw`; vtracer 0.6 treats any other word, `binary` included,
        # as colour mode without a warning.
        measure "vtracer $("$VTRACER" --version | awk '{ print $NF }')" \
            "outline, --colormode bw" "$input" "$work/out/$stem.vtracer.svg" \
            "$VTRACER" --input "$work/$input" --output "$work/out/$stem.vtracer.svg" --colormode bw
    done
else
    skipped+=("vtracer: not installed (cargo install vtracer, or set VTRACER=path)")
fi

if have autotrace; then
    for input in page.pbm page-scan.pbm; do
        stem=${input%.*}
        measure "autotrace" "centerline, PBM → SVG" "$input" "$work/out/$stem.autotrace.svg" \
            autotrace -centerline -input-format pbm -output-format svg \
            -output-file "$work/out/$stem.autotrace.svg" "$work/$input"
    done
else
    skipped+=("autotrace: not installed (Debian bookworm has no autotrace package)")
fi

time_all

echo "Machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//');" \
    "load average $load_before before, $(cut -d' ' -f1-3 /proc/loadavg) after; $RUNS runs a row."
echo
echo "| tool | mode | input | wall median (s) | σ (s) | peak RSS (MiB) | paths | SVG (KiB) |"
echo "|---|---|---|---:|---:|---:|---:|---:|"
for i in "${!commands[@]}"; do
    echo "| ${labels[i]} | ${modes[i]} | ${inputs[i]} | ${walls[i]} | ${sigmas[i]} | ${rsses[i]} |" \
        "${path_counts[i]} | ${sizes[i]} |"
done
for input in page.png page-scan.jpg; do
    mine= theirs=
    for i in "${!commands[@]}"; do
        [[ ${inputs[i]} == "$input" ]] || continue
        case ${labels[i]} in
        crawltrace*) mine=${walls[i]} ;;
        vtracer*) theirs=${walls[i]} ;;
        esac
    done
    if [[ -n $mine && -n $theirs ]]; then
        awk -v a="$mine" -v b="$theirs" -v i="$input" \
            'BEGIN { printf "\ncrawltrace takes %.2f× vtracer'"'"'s wall time on %s.\n", a / b, i }'
    fi
done
if ((${#skipped[@]})); then
    echo
    printf -- '- skipped %s\n' "${skipped[@]}"
fi
echo
echo "Inputs and SVGs: $work"
