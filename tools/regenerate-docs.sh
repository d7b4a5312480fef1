#!/usr/bin/env bash
# Regenerates the tables and figures of docs/ from the commands that produce them.
#
#   tools/regenerate-docs.sh            every generator (the accuracy study and the
#                                       application's screenshots take minutes)
#   tools/regenerate-docs.sh --cheap    only the generators that take seconds
#   tools/regenerate-docs.sh --check    the cheap generators into a scratch copy of docs/;
#                                       fails on any difference in docs/*.md, printing it
#                                       (figures and timings are not compared)
#   tools/regenerate-docs.sh --list     the generators, their cost and what they write
#   tools/regenerate-docs.sh --only NAME   one generator of the list, cheap or slow
#
# Options: --build-dir DIR (default: $BUILD_DIR, else build/). Build imagepro-cli and
# imagepro-studies first (tools/setup.sh build).
#
# Two kinds of generated text:
# * a study's measured places in its hand-written doc (tracking.md, calibration.md,
#   accuracy.md): the study given --out DOC fills every <!--m:NAME-->...<!--/m--> of DOC
#   with its figures and leaves the prose as it is (src/studies/measured_doc.h);
# * blocks inside hand-written docs, between the lines
#     <!-- generated: COMMAND -->        (the output is Markdown, e.g. a table)
#     <!-- generated code: COMMAND -->   (the output is shown in a ``` block)
#     <!-- end generated -->
#   replaced by COMMAND's standard output between blank lines. COMMAND is imagepro-cli or
#   imagepro-studies with plain arguments (no quotes or shell syntax), run from the
#   repository's root.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build_dir="${BUILD_DIR:-$root/build}"
mode=all
only=""
usage() { sed -n '2,14p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//' >&2; exit 2; }
while (($#)); do
  case "$1" in
    --cheap) mode=cheap ;;
    --check) mode=check ;;
    --list) mode=list ;;
    --only) (($# >= 2)) || usage; only="$2"; shift ;;
    --build-dir) (($# >= 2)) || usage; build_dir="$2"; shift ;;
    -h|--help) usage ;;
    *) echo "regenerate-docs: unknown option $1" >&2; usage ;;
  esac
  shift
done
build_dir="$(cd "$build_dir" 2>/dev/null && pwd)" || { echo "regenerate-docs: no build folder $build_dir" >&2; exit 2; }

# The one line of a generated doc that varies from run to run; --check skips it.
timing_lines='^Calibration time on the machine that wrote this: '

# The generators: name, cost (cheap: seconds; slow: minutes or a display), what they write.
generators=(
  "tracking|cheap|docs/tracking.md, docs/tracking-*.png (track-study: the critical r, the runs of figs. 3.7-3.12; under 1 s)"
  "calibration|cheap|the measured places of docs/calibration.md (calibration-study, about 15 s of CPU)"
  "blocks|cheap|the generated blocks of docs/*.md (each a few seconds at most)"
  "case-study-figures|cheap|docs/case-studies-*.png (two-targets --plot, pendulum --plots, 2 s)"
  "distortion-figures|cheap|docs/distortion-*.png (distortion-figures --plots, 1 s)"
  "ellipse-figures|cheap|docs/ellipse-library-*.png, docs/ellipse-accumulator-*.png (ellipse-library --plots, detect --accumulators, 2 s)"
  "accuracy|slow|docs/accuracy.md (accuracy study, virtual and real scenes, a few minutes)"
  "screenshots|slow|docs/app-*.png (the application under xvfb-run, a minute; skipped without it)"
  "python|slow|docs/python.md, docs/python-pose-error.png (docs/python-walkthrough.py run as a notebook, 20 s; needs the Python module and python3-matplotlib)"
)

if [ "$mode" = list ]; then
  for g in "${generators[@]}"; do IFS='|' read -r name cost what <<<"$g"; printf '%-20s %-6s %s\n' "$name" "$cost" "$what"; done
  exit 0
fi

program() {
  case "$1" in
    imagepro-cli) echo "$build_dir/src/cli/imagepro-cli" ;;
    imagepro-studies) echo "$build_dir/src/studies/imagepro-studies" ;;
    *) return 1 ;;
  esac
}
for p in imagepro-cli imagepro-studies; do
  [ -x "$(program $p)" ] || { echo "regenerate-docs: $(program $p) not built (tools/setup.sh build)" >&2; exit 2; }
done

# Where the generators write: the repository, or a scratch copy of docs/ for --check.
scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT
work="$root"
if [ "$mode" = check ]; then
  work="$scratch/repository"
  mkdir "$work"
  cp -r "$root/docs" "$work/docs"
  ln -s "$root/data" "$work/data"
fi

log() { echo "regenerate-docs: $*" >&2; }
step=0
# Runs a documented command (imagepro-cli or imagepro-studies ARGS...) in $work, its
# standard error kept for when it fails.
run_doc_command() {
  local words exe
  read -ra words <<<"$1"
  exe="$(program "${words[0]}")" || { log "not a documented command: $1"; return 1; }
  (cd "$work" && "$exe" "${words[@]:1}" 2>"$scratch/stderr") || { cat "$scratch/stderr" >&2; log "failed: $1"; return 1; }
}
timed() {  # LABEL COMMAND...: one progress line, with the seconds taken
  local label="$1" start=$SECONDS; shift
  step=$((step + 1))
  log "[$step] $label ..."
  "$@" || return 1
  log "[$step] $label: done in $((SECONDS - start)) s"
}

gen_tracking() {
  timed "track-study" run_doc_command "imagepro-studies track-study --frames 250 --out docs/tracking.md" >/dev/null
}

gen_calibration() {
  timed "calibration-study" run_doc_command "imagepro-studies calibration-study --out docs/calibration.md" >/dev/null
}

gen_accuracy() {
  timed "accuracy" run_doc_command \
    "imagepro-studies accuracy --frames 300 --stills 2000 --negatives 500 --videos 4 --video-frames 150 --seed 1" \
    >/dev/null
}

# Every marker block of one doc replaced by its command's output.
fill_blocks() {
  local doc="$1" out="$scratch/block.md" line command code inside=0
  : >"$out"
  while IFS= read -r line || [ -n "$line" ]; do
    if ((inside)); then
      [[ "$line" == "<!-- end generated -->" ]] || continue
      inside=0
    elif [[ "$line" =~ ^\<!--\ generated(\ code)?:\ (.*)\ --\>$ ]]; then
      code="${BASH_REMATCH[1]}" command="${BASH_REMATCH[2]}"
      [[ "$command" =~ ^[A-Za-z0-9./=,_\ -]+$ ]] || { log "$doc: not a plain command: $command"; return 1; }
      # Blank lines around the output: a table runs on into any line that follows it.
      printf '%s\n\n' "$line" >>"$out"
      [ -n "$code" ] && echo '```' >>"$out"
      timed "${doc#"$work"/}: $command" run_doc_command "$command" >>"$out" || return 1
      [ -n "$code" ] && echo '```' >>"$out"
      echo >>"$out"
      inside=1
      continue
    fi
    printf '%s\n' "$line" >>"$out"
  done <"$doc"
  ((inside == 0)) || { log "$doc: a generated block without its end line"; return 1; }
  cat "$out" >"$doc"
}

gen_blocks() {
  local doc
  for doc in "$work"/docs/*.md; do
    grep -q '^<!-- generated' "$doc" && fill_blocks "$doc"
  done
  return 0
}

gen_case_study_figures() {
  local tmp="$scratch/figures"
  mkdir -p "$tmp"
  timed "two-targets figure" run_doc_command \
    "imagepro-cli two-targets --virtual --position 2 --plot $tmp/two-targets" >/dev/null
  cp "$tmp/two-targets-position2-distance.png" "$work/docs/case-studies-two-targets-position2-distance.png"
  timed "pendulum figure" run_doc_command "imagepro-cli pendulum --virtual --plots $tmp" >/dev/null
  cp "$tmp/pendulum-translations.png" "$work/docs/case-studies-pendulum-translations.png"
}

# The lens distortion's fields, their correction and the Taylor inverse's error (thesis 4.2, 4.5).
gen_distortion_figures() {
  timed "distortion figures" run_doc_command "imagepro-studies distortion-figures --plots docs" >/dev/null
}

# Bennett's accumulators and the library's per-image charts (thesis 2.6, appendix B).
gen_ellipse_figures() {
  local tmp="$scratch/ellipse" name
  mkdir -p "$tmp"
  timed "library charts" run_doc_command "imagepro-studies ellipse-library --plots docs" >/dev/null
  timed "library images" run_doc_command "imagepro-cli library $tmp/library" >/dev/null
  timed "accumulators" run_doc_command "imagepro-cli detect --method bennett --accumulators $tmp/acc \
data/samples/sample03_tilted50.png data/samples/sample02_clutter.png $tmp/library/ellipse_69.png $tmp/library/rectangle_66.png" >/dev/null
  cp "$tmp/acc/sample03_tilted50_accumulator.png" "$work/docs/ellipse-accumulator-sample03.png"
  cp "$tmp/acc/sample02_clutter_accumulator.png" "$work/docs/ellipse-accumulator-sample02.png"
  # One picture per shown path; these images show one each (test CliLibrary.DetectWritesBennettsAccumulators).
  for pair in sample03_tilted50:sample03-path ellipse_69:library-ellipse rectangle_66:library-rectangle; do
    set -- "$tmp/acc/${pair%%:*}"_path*.png
    [ $# -eq 1 ] && [ -f "$1" ] || { log "accumulators: not one path picture for ${pair%%:*}"; return 1; }
    cp "$1" "$work/docs/ellipse-accumulator-${pair#*:}.png"
  done
}

# Runs a command that writes the figure PNG (docs/app-*.png); the test program's other
# classes report the function they lack, so its exit code is not the test of success.
screenshot() {
  local png="$1" stamp="$scratch/stamp"; shift
  touch "$stamp"
  timed "$png" bash -c '"$@" >/dev/null 2>&1 || true' _ "$@"
  [ "$png" -nt "$stamp" ] || { log "$png was not written: $*"; return 1; }
}

gen_screenshots() {
  local app="$build_dir/src/app/imagepro" tests="$build_dir/tests/app/test_app" xvfb=()
  if [ -z "${DISPLAY:-}" ]; then
    command -v xvfb-run >/dev/null || { log "screenshots skipped: no display and no xvfb-run (apt-get install xvfb)"; return 0; }
    xvfb=(xvfb-run -a -s "-screen 0 1600x1000x24")
  fi
  [ -x "$app" ] && [ -x "$tests" ] || { log "screenshots skipped: build imagepro and test_app first"; return 0; }
  cd "$root"
  screenshot docs/app-virtual.png env QT_QPA_PLATFORM=xcb "${xvfb[@]}" "$app" \
    --config docs/app-screenshot-settings.json --source virtual --screenshot docs/app-virtual.png --after 7
  screenshot docs/app-file.png env QT_QPA_PLATFORM=xcb "${xvfb[@]}" "$app" data/samples/sample02_clutter.png \
    --screenshot docs/app-file.png --after 2
  screenshot docs/app-calibration-wizard.png env IMAGEPRO_WIZARD_SCREENSHOT=docs/app-calibration-wizard.png \
    QT_QPA_PLATFORM=xcb "${xvfb[@]}" "$tests" recoversTheLensFromVirtualPatternImages
  screenshot docs/app-calibration-wizard-report.png env \
    IMAGEPRO_WIZARD_REPORT_SCREENSHOT=docs/app-calibration-wizard-report.png QT_QPA_PLATFORM=xcb "${xvfb[@]}" \
    "$tests" intrinsicModeRecoversTheCamera
  screenshot docs/app-analysis.png env IMAGEPRO_ANALYSIS_SCREENSHOT=docs/app-analysis.png QT_QPA_PLATFORM=xcb \
    "${xvfb[@]}" "$tests" virtualPendulumGivesG
  screenshot docs/app-calibration-check.png env IMAGEPRO_CALIBRATION_CHECK_SCREENSHOT=docs/app-calibration-check.png \
    QT_QPA_PLATFORM=xcb "${xvfb[@]}" "$tests" overlayMatchesThePatternsTruth
  screenshot docs/app-d0.png env IMAGEPRO_D0_SCREENSHOT=docs/app-d0.png QT_QPA_PLATFORM=xcb \
    "${xvfb[@]}" "$tests" virtualFramesGiveTheirKnownD0
}

# The walk-through of the Python module, run by the Python it was built for, cell by cell.
gen_python() {
  local module="$build_dir/python" python
  python="$(sed -n 's/^Python_EXECUTABLE:[A-Z]*=//p' "$build_dir/CMakeCache.txt")"
  ls "$module"/imagepro.*.so >/dev/null 2>&1 && [ -n "$python" ] || { log "python skipped: the module is not built (IMAGEPRO_PYTHON)"; return 0; }
  "$python" -c "import matplotlib" 2>/dev/null || { log "python skipped: no matplotlib (apt-get install python3-matplotlib)"; return 0; }
  timed "python walk-through" bash -c 'cd "$1" && PYTHONPATH="$2" "$3" "$4" docs/python-walkthrough.py --out docs/python.md' \
    _ "$work" "$module" "$python" "$root/tools/python-notebook.py"
}

for g in "${generators[@]}"; do
  IFS='|' read -r name cost _ <<<"$g"
  if [ -n "$only" ]; then
    [ "$name" = "$only" ] || continue
  elif [ "$mode" != all ] && [ "$cost" != cheap ]; then
    continue
  fi
  "gen_${name//-/_}"
  ran=1
done
[ -n "${ran:-}" ] || { echo "regenerate-docs: no generator $only (--list names them)" >&2; exit 2; }

if [ "$mode" = check ]; then
  status=0
  for doc in "$root"/docs/*.md; do
    diff -u -I "$timing_lines" --label "$doc (committed)" --label "$doc (regenerated)" \
      "$doc" "$work/docs/$(basename "$doc")" || status=1
  done
  if ((status)); then
    log "docs/ differs from what its commands print now: run tools/regenerate-docs.sh --cheap and commit"
    exit 1
  fi
  log "docs/ matches its generators"
fi
