#!/bin/sh
# Regenerates data/samples/: the sample frames of the File source, rendered by
# imagepro-cli render with the shipped settings (data/settings.json), and their
# exact poses in data/samples/truth.csv. They keep the plain backdrop of the thesis's
# synthetic frames.
#   usage: tools/make-samples.sh [path/to/imagepro-cli]   (default: build/src/cli/imagepro-cli)
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
cli=${1:-$root/build/src/cli/imagepro-cli}
out=$root/data/samples
mkdir -p "$out"
rm -f "$out"/sample*.png "$out"/truth.csv

render() {
  "$cli" render --config "$root/data/settings.json" --out "$out" --frames 1 --append --mode grey --backdrop plain "$@"
}

# Facing the camera, centred.
render --name sample01_facing --pose 0,0,0,0,0,800
# Turned about all three axes, off centre, among clutter.
render --name sample02_clutter --pose 25,-20,15,60,-40,700 --clutter 10 --seed 3
# Tilted 50 degrees about Y.
render --name sample03_tilted50 --pose 0,50,10,-40,20,750
# Dim lighting: low contrast and a strong illumination gradient.
render --name sample04_dim --pose 10,15,-30,-80,50,900 --white 90 --black 10 --background 40 --gradient 0.6
# Sensor noise and defocus blur, with clutter.
render --name sample05_noise_blur --pose -20,30,45,100,60,850 --noise 6 --blur 1.2 --clutter 6 --seed 5
# No target in view (it is far to the side): clutter only.
render --name sample06_no_target --pose 0,0,0,2000,0,800 --clutter 12 --seed 8
# The thesis's binary image (figure 2.4).
render --name sample07_binary --pose 30,-35,20,-30,-20,650 --mode binary
# The calibration pattern, turned about 30 degrees as thesis 4.5 recommends.
render --name sample08_pattern --pose 30,-25,0,0,0,1100 --pattern
