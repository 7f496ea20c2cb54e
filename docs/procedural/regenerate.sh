#!/usr/bin/env bash
# Regenerates the pictures and tables of docs/procedural.md (technique `procedural`, paper 2) on
# whatever adapter this machine has (WGPU_BACKEND / WGPU_ADAPTER_NAME choose it). Needs python3 with
# numpy and Pillow for the map pictures and the contact sheet.
#   docs/procedural/regenerate.sh            everything (renders, compare, bench: ~5 min on lavapipe)
#   docs/procedural/regenerate.sh --no-bench  without the timings
set -euo pipefail
cd "$(dirname "$0")/../.."
cargo build --release -q
bin=target/release/caustics
out=docs/procedural
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# 1. The three variants, same frame of the pool (time 0), final image and raw map. The screen-space
#    variant is evaluated per pixel at 1024 x 1024 over the 4 m pool: about one map texel per image
#    pixel where the floor is nearest the camera (`caustics render` samples the map bilinearly per
#    image pixel, so "per pixel in screen space" is the map at the image's resolution).
for v in vertex screen texture; do
  $bin render --scene pool --technique procedural-$v --map-size 1024 \
    --out $out/pool-$v.png --raw "$tmp/pool-$v.npy"
done
$bin render --scene pool --technique reference --map-size 512 --out $out/pool-reference.png

# 2. Aliasing: paper 2's own wave function, whose frequency grows with x·y, into a 256² map: per
#    pixel (point sampling) against the texture-space target of 1024² read through its mip chain.
$bin render --scene $out/paper-wave.toml --technique procedural-screen --raw "$tmp/paper-screen.npy" \
  --out $out/paper-screen.png
$bin render --scene $out/paper-wave.toml --technique procedural-texture:target_resolution=1024 \
  --raw "$tmp/paper-texture.npy" --out $out/paper-texture.png
$bin render --scene $out/paper-wave.toml \
  --technique procedural-texture:target_resolution=1024,anisotropy=1 --raw "$tmp/paper-trilinear.npy"
$bin render --scene $out/paper-wave.toml --technique procedural-screen --map-size 4096 \
  --raw "$tmp/paper-truth.npy"

# 3. An animated sequence: 8 frames of the pool, 0.1 s apart (the longest wave's period is 0.8 s).
for k in 0 1 2 3 4 5 6 7; do
  $bin render --scene pool --technique procedural --time "0.$k" --image-size 480x270 \
    --out "$tmp/frame-$k.png"
done

python3 - "$tmp" "$out" <<'EOF'
import sys
import numpy as np
from PIL import Image

tmp, out = sys.argv[1], sys.argv[2]

def picture(m, path, size=None):
    # min(E, 1) in sRGB: flat water white, no light black; row 0 (y = 0) at the bottom.
    v = np.clip(m, 0.0, 1.0)
    s = np.where(v <= 0.0031308, 12.92 * v, 1.055 * v ** (1 / 2.4) - 0.055)
    img = Image.fromarray((s[::-1] * 255 + 0.5).astype(np.uint8), "L")
    if size:
        img = img.resize((size, size), Image.LANCZOS)
    img.save(path)

for v in ["vertex", "screen", "texture"]:
    m = np.load(f"{tmp}/pool-{v}.npy")
    picture(m, f"{out}/map-pool-{v}.png", 512)
    # A 1 m x 1 m corner of the pool at the map's own resolution (256 x 256 texels).
    picture(m[:256, :256], f"{out}/map-pool-{v}-detail.png")

truth = np.load(f"{tmp}/paper-truth.npy").reshape(256, 16, 256, 16).mean(axis=(1, 3))
picture(truth, f"{out}/map-paper-truth.png")
rows = []
for v in ["screen", "texture", "trilinear"]:
    m = np.load(f"{tmp}/paper-{v}.npy")
    picture(m, f"{out}/map-paper-{v}.png")
    f = np.abs(np.fft.fft2(m - m.mean())) ** 2
    fy = np.abs(np.fft.fftfreq(m.shape[0]))[:, None]
    fx = np.abs(np.fft.fftfreq(m.shape[1]))[None, :]
    high = f[np.maximum(fx, fy) > 0.25].sum() / f.sum()
    rows.append((v, np.sqrt(((m - truth) ** 2).mean()), np.abs(m - truth).mean(), high))
ft = np.abs(np.fft.fft2(truth - truth.mean())) ** 2
fy = np.abs(np.fft.fftfreq(256))[:, None]
fx = np.abs(np.fft.fftfreq(256))[None, :]
rows.append(("truth", 0.0, 0.0, ft[np.maximum(fx, fy) > 0.25].sum() / ft.sum()))
with open(f"{out}/aliasing.md", "w") as fh:
    fh.write("| map (256²) | RMS against the truth | mean abs | energy above half Nyquist |\n|---|---|---|---|\n")
    names = {"screen": "procedural-screen (point sampling)",
             "texture": "procedural-texture, target 1024², anisotropy 16 (lavapipe: EWA)",
             "trilinear": "procedural-texture, target 1024², anisotropy 1 (trilinear)",
             "truth": "truth: per pixel at 4096², 16 x 16 box average"}
    for v, rms, mae, high in rows:
        v = names[v]
        fh.write(f"| {v} | {rms:.4f} | {mae:.4f} | {100 * high:.1f} % |\n")

frames = [Image.open(f"{tmp}/frame-{k}.png") for k in range(8)]
w, h = frames[0].size
sheet = Image.new("RGB", (4 * w, 2 * h), "white")
for k, f in enumerate(frames):
    sheet.paste(f, ((k % 4) * w, (k // 4) * h))
    f.save(f"{out}/pool-t{k}.png")
sheet.save(f"{out}/pool-sequence.png")
EOF

# 4. Against the reference (the generated cases of `caustics compare`).
$bin compare --technique procedural --technique procedural-vertex --technique procedural-texture \
  --technique procedural:follow_sun=true --map-size 256 \
  --picture-cases waves-mid-deep,lens-low-deep,ocean-overhead-shallow,ripples-low-shallow \
  --out "$tmp/compare"
sed -n '/^Generated by/p;/^## Summary/,/^## Every case/p' "$tmp/compare/compare.md" | sed '$d' > $out/compare-summary.md
cp "$tmp/compare/compare.csv" $out/compare.csv
cp "$tmp"/compare/lens-low-deep-procedural-256.png "$tmp"/compare/ripples-low-shallow-procedural-texture-256.png \
  "$tmp"/compare/ocean-overhead-shallow-procedural-256.png "$tmp"/compare/ocean-overhead-shallow-procedural-texture-256.png \
  "$tmp"/compare/waves-mid-deep-procedural-256.png "$tmp"/compare/waves-mid-deep-procedural_follow_sun_true-256.png $out/

# 5. Timings per variant and pass.
if [ "${1:-}" != "--no-bench" ]; then
  $bin bench --technique procedural-vertex --technique procedural-screen --technique procedural-texture \
    --map-size 512,1024,1920x1080 --frames 20 --warmup 3 --out "$tmp/bench"
  cp "$tmp/bench/bench.md" "$tmp/bench/bench.csv" "$tmp/bench/bench.svg" $out/
fi
echo "wrote $out"
