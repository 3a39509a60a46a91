#!/usr/bin/env bash
# The COLMAP 3.8 peer (CPU): every STEP-th frame of VIDEO, shrunk to MAX_SIDE
# pixels, through feature_extractor (one SIMPLE_PINHOLE camera per frame, so
# the focal is free per frame), sequential_matcher and the incremental mapper;
# the largest model is converted with `hapcine convert --from-colmap` (which
# gives frames COLMAP did not see or register confidence 0) and
# hapcine_path_fill interpolates between the registered frames.
#   bench/colmap_peer.sh VIDEO OUT.camera.csv STEP MAX_SIDE BUILD_DIR
set -euo pipefail
video=$1 out=$2 step=$3 max_side=$4 build=$5
work=$(mktemp -d "${TMPDIR:-/tmp}/hapcine-bench-colmap-XXXXXX")
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/images" "$work/sparse" "$work/txt"
fps=$(ffprobe -v error -select_streams v:0 -show_entries stream=r_frame_rate -of csv=p=0 "$video" | awk -F/ '{print ($2 ? $1/$2 : $1)}')
ffmpeg -nostdin -loglevel error -i "$video" \
  -vf "select=not(mod(n\,$step)),scale='if(gte(iw,ih),min($max_side,iw),-2)':'if(gte(iw,ih),-2,min($max_side,ih))'" \
  -vsync passthrough -start_number 0 -q:v 2 "$work/images/seq_%06d.jpg"
# Name every image after its frame index in the video (k-th kept image = frame k * step).
for f in "$work"/images/seq_*.jpg; do
  k=$((10#$(basename "$f" .jpg | sed 's/seq_//')))
  mv "$f" "$work/images/frame_$(printf %06d $((k * step))).jpg"
done
db="$work/database.db"
log="$work/colmap.log"
run() { colmap "$@" >>"$log" 2>&1 || { echo "colmap $1 failed: $(tail -n 2 "$log" | tr '\n' ' ')" >&2; exit 1; }; }
run feature_extractor --database_path "$db" --image_path "$work/images" \
  --ImageReader.single_camera 0 --ImageReader.camera_model SIMPLE_PINHOLE \
  --SiftExtraction.use_gpu 0 --SiftExtraction.num_threads 2 --SiftExtraction.max_num_features 1024
run sequential_matcher --database_path "$db" --SiftMatching.use_gpu 0 --SiftMatching.num_threads 2 \
  --SequentialMatching.overlap 5
run mapper --database_path "$db" --image_path "$work/images" --output_path "$work/sparse" --Mapper.num_threads 2
best="" best_n=0
for m in "$work"/sparse/*/; do
  [ -f "$m/cameras.bin" ] || continue
  colmap model_converter --input_path "$m" --output_path "$m" --output_type TXT >>"$log" 2>&1
  n=$(grep -v '^#' "$m/images.txt" | grep -c . || true)
  n=$((n / 2))
  if [ "$n" -gt "$best_n" ]; then best=$m; best_n=$n; fi
done
[ -n "$best" ] || { echo "colmap mapper made no model (no initial pair: pure rotation or static camera?)" >&2; exit 1; }
"$build/cli/hapcine" convert --from-colmap "$best" --times-from "$video" -o "$work/keyframes.camera.csv" >>"$log" 2>&1 ||
  { echo "hapcine convert failed: $(tail -n 1 "$log")" >&2; exit 1; }
"$build/bench/hapcine_path_fill" "$work/keyframes.camera.csv" "$out" --fps "$fps" --max-gap $((2 * step))
echo "colmap: $best_n of $(ls "$work/images" | wc -l) images registered (1 frame in $step, ${max_side} px)" >&2
