#!/usr/bin/env bash
# Mutation check of the WGSL passes ("a 1 % change to the output of any WGSL pass, or the
# loss of any channel, layer or cascade, fails at least one test").
#
# For each mutation below: edit one WGSL file under crates/gpu/src (most scale what the pass
# writes by 1.01; index, count and bound outputs get an off-by-one or a 1 % tighter bound instead),
# rebuild caustics-gpu's test binaries that exercise that pass (build.rs compiles the WGSL, so
# only caustics-gpu and its tests rebuild), check the mutated shader still validates (else the
# mutation proves nothing), run those tests, record which failed, and put the file back (a trap
# restores it on any exit). Prints a table; results also go to $OUT (default mutations.tsv).
#
# Run it in a worktree nobody edits meanwhile (it rewrites shader files), under nice:
#   nice -n 10 scripts/mutate-passes.sh [NAME-FILTER]
# Needs Vulkan (lavapipe will do); GPU tests run with CAUSTICS_REQUIRE_GPU=1 so a missing device
# fails loudly instead of counting as "not caught".
set -u
cd "$(dirname "$0")/.."
ROOT=$(pwd)
OUT=${OUT:-$ROOT/mutations.tsv}
LOG=${LOG:-$ROOT/mutations.log}
FILTER=${1:-}
export WGPU_BACKEND=${WGPU_BACKEND:-vulkan} CAUSTICS_REQUIRE_GPU=1
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp/xdg-mutate-$$}
mkdir -p "$XDG_RUNTIME_DIR" && chmod 700 "$XDG_RUNTIME_DIR"
# Only the workspace crates rebuild per mutation; incremental builds keep that to the changed code.
export CARGO_PROFILE_RELEASE_INCREMENTAL=${CARGO_PROFILE_RELEASE_INCREMENTAL:-true}

S=crates/gpu/src
YU="yuksel_gpu technique_gpu render_gpu"
CA="cascaded_gpu render_gpu"
PR="procedural_gpu"
CT="caustic_triangles_gpu"
VO="volumes_gpu"
WA="water_gpu water_field_gpu"
FI="render_gpu caustic_triangles_gpu"

# name @@ file @@ exact text @@ replacement (every occurrence) @@ test files
MUTATIONS=$(cat <<EOF
probe x1.01 @@ $S/probe.wgsl @@ outputs[k] = o; @@ o.refracted *= 1.01; o.fresnel_sine_procedural *= 1.01; o.procedural *= 1.01; o.grid *= 1.01; outputs[k] = o; @@ shared_math
yuksel prepass record flux x1.01 @@ $S/yuksel/sample.wgsl @@ f.rec.w / f32(t * t)); @@ f.rec.w * 1.01 / f32(t * t)); @@ $YU
yuksel footprint flux ramp dropped @@ $S/yuksel/sample.wgsl @@ const RAMP_WEIGHT: f32 = 4.0; @@ const RAMP_WEIGHT: f32 = 0.0; @@ yuksel_gpu
yuksel prepass tiles overlap @@ $S/yuksel/common.wgsl @@ (xy.y / t.y) * i32(u.pre_tiles) + xy.x / t.x @@ xy.x / t.x @@ limits_gpu
yuksel pass1 x1.01 @@ $S/yuksel/pass1.wgsl @@ += ax * ay * p.w * area; @@ += ax * ay * p.w * area * 1.01; @@ $YU
yuksel pass1 last channel lost @@ $S/yuksel/pass1.wgsl @@ i32(region.m) + 1); @@ i32(region.m)); @@ $YU
yuksel pass2 x1.01 @@ $S/yuksel/pass2.wgsl @@ vec4<f32>(e * u.attenuation.rgb, 1.0) @@ vec4<f32>(e * 1.01 * u.attenuation.rgb, 1.0) @@ $YU
yuksel pass2 last channel lost @@ $S/yuksel/pass2.wgsl @@ k <= m; @@ k < m; @@ $YU
water patches x1.01 @@ $S/water/water_patches.wgsl @@ let texel = grid_hermite_texel(heights, vec2<i32>(id.xy), patches_params.wrap != 0u); @@ let texel = grid_hermite_texel(heights, vec2<i32>(id.xy), patches_params.wrap != 0u) * 1.01; @@ $YU
yuksel scatter resolve x1.01 @@ $S/yuksel/scatter_resolve.wgsl @@ vec4<f32>(e * u.attenuation.rgb, 1.0) @@ vec4<f32>(e * 1.01 * u.attenuation.rgb, 1.0) @@ $YU
yuksel scatter tier flux x1.01 @@ $S/yuksel/scatter_tier.wgsl @@ add_record(tier_records[r], q); @@ add_record(tier_records[r] * vec4<f32>(1.0, 1.0, 1.0, 1.01), q); @@ $YU
yuksel fill next row's edge from this row's hit @@ $S/yuksel/fill.wgsl @@ fill_below[a] = above; @@ fill_below[a] = h; @@ $YU
yuksel prepass fill last listed pixel lost @@ $S/yuksel/prepass_fill.wgsl @@ entry < fill_args[3] @@ entry + 1u < fill_args[3] @@ $YU
yuksel scatter fill last listed pixel lost @@ $S/yuksel/scatter_fill.wgsl @@ entry < fill_args[3] @@ entry + 1u < fill_args[3] @@ $YU
yuksel region one row fewer @@ $S/yuksel/region.wgsl @@ out.m = u32(y.x - 1); @@ out.m = u32(y.x - 2); @@ $YU
yuksel region 1 % narrower bound @@ $S/yuksel/region.wgsl @@ let margin = (hi - lo) * 0.125; @@ let margin = (hi - lo) * 0.12; @@ $YU
yuksel walls let light in from beyond the square @@ $S/yuksel/sample.wgsl @@ if f.rec.w == 0.0 || beyond { @@ if f.rec.w == 0.0 { @@ $YU
yuksel footprint 1 % wider @@ $S/yuksel/sample.wgsl @@ yp.y - ym.y)) * 0.5 / pixel; @@ yp.y - ym.y)) * 0.505 / pixel; @@ $YU
cascaded eye x1.01 @@ $S/cascaded/eye.wgsl @@ textureStore(eye_out, vec2<i32>(id.xy), out); @@ textureStore(eye_out, vec2<i32>(id.xy), out * 1.01); @@ $CA
cascaded water x1.01 @@ $S/cascaded/water.wgsl @@ vec4<f32>(s, height_field_normal(grad)) @@ vec4<f32>(s, height_field_normal(grad)) * 1.01 @@ $CA
cascaded terrain x1.01 @@ $S/cascaded/terrain.wgsl @@ vec4<f32>(s, 0.0, 0.0, 0.0) @@ vec4<f32>(s * 1.01, 0.0, 0.0, 0.0) @@ $CA
cascaded photons x1.01 @@ $S/cascaded/photons.wgsl @@ photon_weight(ph, ior, c) * cfg.ramps.w @@ photon_weight(ph, ior, c) * 1.01 * cfg.ramps.w @@ $CA
cascaded compose x1.01 @@ $S/cascaded/compose.wgsl @@ out = vec4<f32>(v, f32(k) + b); @@ out = vec4<f32>(v * 1.01, f32(k) + b); @@ $CA
cascaded compose last cascade lost @@ $S/cascaded/compose.wgsl @@ for (var n = 0u; n < 4u; n++) { @@ for (var n = 0u; n < 3u; n++) { @@ $CA
cascaded disperse x1.01 @@ $S/cascaded/disperse.wgsl @@ textureStore(image, vec2<i32>(id.xy), out); @@ textureStore(image, vec2<i32>(id.xy), out * 1.01); @@ $CA
procedural vertex x1.01 @@ $S/procedural/vertex.wgsl @@ vec4<f32>(in.caustic, 1.0) @@ vec4<f32>(in.caustic * 1.01, 1.0) @@ $PR
procedural screen x1.01 @@ $S/procedural/screen.wgsl @@ vec4<f32>(procedural_caustic(p), 1.0) @@ vec4<f32>(procedural_caustic(p) * 1.01, 1.0) @@ $PR
procedural target x1.01 @@ $S/procedural/target.wgsl @@ vec4<f32>(procedural_caustic(p), 1.0) @@ vec4<f32>(procedural_caustic(p) * 1.01, 1.0) @@ $PR
procedural downsample x1.01 @@ $S/procedural/downsample.wgsl @@ (a + b + d + e) * 0.25 @@ (a + b + d + e) * 0.2525 @@ $PR
procedural resample x1.01 @@ $S/procedural/resample.wgsl @@ vec4<f32>(c.rgb, 1.0) @@ vec4<f32>(c.rgb * 1.01, 1.0) @@ $PR
ocean spectrum x1.01 @@ $S/water/ocean_spectrum.wgsl @@ vec4<f32>(cmul(h, s), cmul(slope, s)); @@ vec4<f32>(cmul(h, s), cmul(slope, s)) * 1.01; @@ $WA
ocean fft x1.01 @@ $S/water/ocean_fft.wgsl @@ = u0 @@ = 1.01 * u0 @@ $WA
ocean output x1.01 @@ $S/water/ocean_output.wgsl @@ vec4<f32>(v.x, v.z, v.w, 0.0) @@ vec4<f32>(v.x, v.z, v.w, 0.0) * 1.01 @@ $WA
ripple step x1.01 @@ $S/water/ripple_step.wgsl @@ vec4<f32>(next, 0.0, 0.0, 0.0) @@ vec4<f32>(next * 1.01, 0.0, 0.0, 0.0) @@ $WA
ripple drop x1.01 @@ $S/water/ripple_drop.wgsl @@ vec4<f32>(bump, 0.0, 0.0, 0.0) @@ vec4<f32>(bump * 1.01, 0.0, 0.0, 0.0) @@ $WA
ripple clear leaves 1e-3 @@ $S/water/ripple_clear.wgsl @@ vec4<f32>(0.0) @@ vec4<f32>(1e-3) @@ $WA
field waves x1.01 @@ $S/water/water_field_waves.wgsl @@ field.amplitude * h @@ field.amplitude * h * 1.01 @@ $WA
field procedural x1.01 @@ $S/water/water_field_procedural.wgsl @@ field.amplitude * h @@ field.amplitude * h * 1.01 @@ $WA
field grid x1.01 @@ $S/water/water_field_grid.wgsl @@ field.amplitude * h @@ field.amplitude * h * 1.01 @@ $WA
final image x1.01 @@ $S/final_image/final_image.wgsl @@ vec4<f32>(tone_map(c, params.tone_map), 1.0) @@ vec4<f32>(tone_map(c, params.tone_map) * 1.01, 1.0) @@ $FI
final image slab bound 1 % low @@ $S/final_image/final_image_slab.wgsl @@ bitcast<u32>(abs(h.x)) @@ bitcast<u32>(abs(h.x) * 0.99) @@ $FI
final image slab slope 1 % low @@ $S/final_image/final_image_slab.wgsl @@ bitcast<u32>(length(h.yz)) @@ bitcast<u32>(length(h.yz) * 0.99) @@ $FI
filtered water: slopes base x1.01 @@ $S/final_image/water_slopes_base.wgsl @@ first += vec4<f32>(g, g * g) * w; @@ first += vec4<f32>(g, g * g) * w * 1.01; @@ render_gpu
filtered water: slopes halve x1.01 @@ $S/final_image/water_slopes_halve.wgsl @@ n += 1.0; @@ n += 0.99; @@ render_gpu
filtered water: rough water sky x1.01 @@ $S/final_image/final_image_rough_water.wgsl @@ reflected += sky_without_sun(reflect(d, facet)) * ((1.0 - t) * w); @@ reflected += sky_without_sun(reflect(d, facet)) * ((1.0 - t) * w * 1.01); @@ render_gpu
filtered water: glint x1.01 @@ $S/final_image/final_image_rough_water.wgsl @@ return sun_radiance() * (3.14159265 * f * g); @@ return sun_radiance() * (3.14159265 * f * g * 1.01); @@ render_gpu
filtered water: from below, slopes x1.01 @@ $S/final_image/final_image_march.wgsl @@ n = height_field_normal(water_slopes(p, d).mean); @@ n = height_field_normal(water_slopes(p, d).mean * 1.01); @@ render_gpu
final image surface grid not raised @@ $S/final_image/final_image_surface.wgsl @@ params.water_level + h + raise @@ params.water_level + h @@ render_gpu
final image terrain crossing 1000 times looser @@ $S/final_image/final_image_march.wgsl @@ if abs(gm) < ROOT_TOLERANCE * step || @@ if abs(gm) < 1000.0 * ROOT_TOLERANCE * step || @@ render_gpu
final image surface crossing 1000 times looser @@ $S/final_image/final_image_march.wgsl @@ g_hi, ROOT_TOLERANCE * min_step); @@ g_hi, 1000.0 * ROOT_TOLERANCE * min_step); @@ render_gpu
final image crossing's gradient kept swapped @@ $S/final_image/final_image_march.wgsl @@ return last_read.zw; @@ return last_read.wz; @@ render_gpu
shading rule: flat water's light x1.01 @@ $S/shaders/caustics_light.wgsl @@ return exp(-absorption * (depth / cos_t)) @@ return 1.01 * exp(-absorption * (depth / cos_t)) @@ shared_math render_gpu
shading rule: sun through water x1.01 @@ $S/shaders/caustics_light.wgsl @@ return relative * (horizontal * transmittance * shadow); @@ return relative * (horizontal * transmittance * shadow * 1.01); @@ render_gpu
shading rule: sun under water 1 % steeper @@ $S/shaders/caustics_light.wgsl @@ return vec3<f32>(to_sun.xy / ior, cos_t); @@ return vec3<f32>(to_sun.xy / ior, cos_t * 1.01); @@ shared_math
caustics sampling: eye-space image x1.01 @@ $S/shaders/caustics_sampling.wgsl @@ return vec4<f32>(sum / weight, 1.0); @@ return vec4<f32>(sum * 1.01 / weight, 1.0); @@ $CA
caustics sampling: floor map x1.01 @@ $S/shaders/caustics_sampling.wgsl @@ return sum / taps; @@ return sum * 1.01 / taps; @@ render_gpu
caustics sampling: wall map x1.01 @@ $S/shaders/caustics_sampling.wgsl @@ = textureLoad(walls, @@ = 1.01 * textureLoad(walls, @@ render_gpu
caustics sampling: wrapped second texel the first's @@ $S/shaders/caustics_sampling.wgsl @@ c1 = select(c0 + 1, vec2<i32>(0), c0 + 1 == dims); @@ c1 = c0; @@ render_gpu
map mips x1.01 @@ $S/map_mips.wgsl @@ (a + b + e + d) * 0.25 @@ (a + b + e + d) * 0.2525 @@ render_gpu
yuksel region bound 1 % short @@ $S/yuksel/region_bound.wgsl @@ let d = tr.xy / -tr.z * max(u.depth + h, 0.0); @@ let d = tr.xy / -tr.z * max(u.depth + h, 0.0) * 0.99; @@ $YU
yuksel prepass record flux x1.01 in the texture @@ $S/yuksel/prepass.wgsl @@ textureStore(pre_out, at.xy, at.z, rec); @@ textureStore(pre_out, at.xy, at.z, rec * vec4<f32>(1.0, 1.0, 1.0, 1.01)); @@ $YU
yuksel prepass span 1 % narrower @@ $S/yuksel/prepass_span.wgsl @@ vec4<f32>(span, 0.0, 0.0)); @@ vec4<f32>(span * 0.99, 0.0, 0.0)); @@ $YU
triangles band bound slope 1 % low @@ $S/caustic_triangles/band_bound.wgsl @@ ordered(max(abs(hx - h) / dx, abs(hy - h) / dy)) @@ ordered(max(abs(hx - h) / dx, abs(hy - h) / dy) * 0.99) @@ $CT
triangles photon x1.01 @@ $S/caustic_triangles/photon.wgsl @@ = trace_photon(id.y, id.x); @@ = trace_photon(id.y, id.x) * 1.01; @@ $CT
triangles irradiance x1.01 @@ $S/caustic_triangles/irradiance.wgsl @@ = vertex_irradiance(i32(id.y), i32(id.x)); @@ = vertex_irradiance(i32(id.y), i32(id.x)) * 1.01; @@ $CT
triangles hat edge share 1 % more @@ $S/caustic_triangles/irradiance.wgsl @@ select(1.0, 0.5, i == 0 || i == l) @@ select(1.0, 0.505, i == 0 || i == l) @@ $CT
triangles triangles x1.01 @@ $S/caustic_triangles/triangles.wgsl @@ return vec4<f32>(in.light, 1.0); @@ return vec4<f32>(in.light * 1.01, 1.0); @@ $CT
triangles splat x1.01 @@ $S/caustic_triangles/splat.wgsl @@ vec4<f32>(in.e, 1.0) @@ vec4<f32>(in.e * 1.01, 1.0) @@ $CT
triangles pyramid x1.01 @@ $S/caustic_triangles/pyramid.wgsl @@ = vec4<f32>(phi, @@ = vec4<f32>(phi * 1.01, @@ $CT
triangles cube x1.01 @@ $S/caustic_triangles/cube.wgsl @@ vec4<f32>(in.e, in.e * in.d, 0.0, 0.0) @@ vec4<f32>(in.e, in.e * in.d, 0.0, 0.0) * 1.01 @@ $CT
triangles shadow x1.01 @@ $S/caustic_triangles/shadow.wgsl @@ shadow[k] = best; @@ shadow[k] = best * 1.01; @@ $CT
triangles water photon x1.01 @@ $S/caustic_triangles/water_photon.wgsl @@ let power = w.water.z * w.water.z * seen * fresnel; @@ let power = w.water.z * w.water.z * seen * fresnel * 1.01; @@ $CT
triangles water photon path x1.01 @@ $S/caustic_triangles/water_photon.wgsl @@ paths[k] = d; @@ paths[k] = d * 1.01; @@ $CT
triangles water photons upwind lattice dropped @@ $S/caustic_triangles/water_photon.wgsl @@ let s = w.origin.xy + @@ let s = @@ $CT
triangles band one quad fewer drawn @@ $S/caustic_triangles/band.wgsl @@ array<u32, 4>(min(6u * most, 6u * quads * quads), @@ array<u32, 4>(min(6u * most, 6u * quads * quads) - 6u, @@ $CT
triangles band one column narrower @@ $S/caustic_triangles/band.wgsl @@ out.band = band; @@ out.band = band - 1u; @@ $CT
triangles distance map last layer lost @@ $S/caustic_triangles/distance_map.wgsl @@ let layers = min(dmg.layers, MAX_LAYERS); @@ let layers = min(dmg.layers, MAX_LAYERS) - 1u; @@ $CT
triangles camera x1.01 @@ $S/caustic_triangles/camera.wgsl @@ vec4<f32>(radiance(cam.position.xyz, d), 1.0) @@ vec4<f32>(radiance(cam.position.xyz, d) * 1.01, 1.0) @@ $CT
volumes depth x1.01 @@ $S/volumes/depth.wgsl @@ textureStore(out_depth, vec2<i32>(id.xy), best); @@ textureStore(out_depth, vec2<i32>(id.xy), best * 1.01); @@ $VO
volumes water x1.01 @@ $S/volumes/water.wgsl @@ v.pos.w = weight; @@ v.pos.w = weight * 1.01; @@ $VO
volumes slices x1.01 @@ $S/volumes/slices.wgsl @@ vec4<f32>(in.intensity * cos_n, 0.0) @@ vec4<f32>(in.intensity * cos_n * 1.01, 0.0) @@ $VO
volumes floor x1.01 @@ $S/volumes/floor.wgsl @@ vec4<f32>(in.intensity * -normalize(in.dir).z, 0.0) @@ vec4<f32>(in.intensity * -normalize(in.dir).z * 1.01, 0.0) @@ $VO
volumes shade diffuse x1.01 @@ $S/volumes/shade.wgsl @@ textureStore(out_diffuse, ij, d); @@ textureStore(out_diffuse, ij, d * 1.01); @@ $VO
volumes shade image x1.01 @@ $S/volumes/shade.wgsl @@ textureStore(out_image, ij, io); @@ textureStore(out_image, ij, io * 1.01); @@ $VO
volumes view x1.01 @@ $S/volumes/view.wgsl @@ vec4<f32>(colour, 1.0) @@ vec4<f32>(colour * 1.01, 1.0) @@ $VO
volumes walls x1.01 @@ $S/volumes/walls.wgsl @@ vec4<f32>(in.intensity * dot(normalize(in.dir), wall_normal(in.wall)), 0.0) @@ vec4<f32>(in.intensity * dot(normalize(in.dir), wall_normal(in.wall)) * 1.01, 0.0) @@ $VO
volumes walls last wall lost @@ $S/volumes/walls.wgsl @@ if !s.ok || @@ if wall == 3u || !s.ok || @@ $VO
volumes view wall light x1.01 @@ $S/volumes/view.wgsl @@ i32(k), 0).xyz; @@ i32(k), 0).xyz * 1.01; @@ $VO
receivers lookup x1.01 @@ $S/receivers_lookup.wgsl @@ vec4<f32>(rgb, 1.0) @@ vec4<f32>(rgb * 1.01, 1.0) @@ $CT yuksel_gpu $PR $VO
receivers meet 1 % short @@ $S/shaders/receivers.wgsl @@ return m; @@ return 0.99 * m; @@ $CT yuksel_gpu $VO
receivers heights half a texel off @@ $S/shaders/receivers.wgsl @@ let u = (q - r.view.xy) / r.view.z - 0.5; @@ let u = (q - r.view.xy) / r.view.z; @@ $CT yuksel_gpu $VO
receivers share without its depth test @@ $S/shaders/receivers.wgsl @@ if p.z < receiver_height(map, r, light_space(p, t0)) - bias { @@ if p.z < receiver_height(map, r, light_space(p, t0)) - bias - 1.0 { @@ render_gpu
final image objects' deposit 10 % further along the path @@ $S/final_image/final_image_shade.wgsl @@ let path = (params.water_level - p.z) / -t0.z; @@ let path = 1.1 * (params.water_level - p.z) / -t0.z; @@ render_gpu
volumes meets the receivers 1 % further along the ray @@ $S/volumes/meet.wgsl @@ light_space(v.pos.xyz + v.dir.xyz * d, r.t0.xyz) @@ light_space(v.pos.xyz + v.dir.xyz * d * 1.01, r.t0.xyz) @@ $VO
volumes floor over receivers x1.01 @@ $S/volumes/floor_receivers.wgsl @@ return vec4<f32>(in.intensity, 0.0); @@ return vec4<f32>(in.intensity * 1.01, 0.0); @@ $VO
EOF
)

CURRENT=""
restore() {
    if [ -n "$CURRENT" ] && [ -f "$CURRENT.mutate-orig" ]; then
        mv -f "$CURRENT.mutate-orig" "$CURRENT"
    fi
    CURRENT=""
}
trap restore EXIT
trap 'restore; exit 130' INT TERM

# Apply "old -> new" to every occurrence in FILE; exit 3 when OLD is not there (the table is stale).
apply() {
    python3 - "$1" "$2" "$3" <<'PY'
import sys
path, old, new = sys.argv[1:]
text = open(path).read()
if old not in text:
    sys.exit(3)
open(path, "w").write(text.replace(old, new))
PY
}

# The tests of one file that failed (libtest-mimic prints "test NAME ... FAILED").
failed_tests() {
    grep -E '^test .* \.\.\. FAILED' "$1" | sed -E 's/^test (.*) \.\.\. FAILED.*/\1/'
}

: > "$LOG"
printf 'pass\tmutation\tresult\tcaught by\n' > "$OUT"
while IFS= read -r line; do
    [ -z "$line" ] && continue
    name=$(echo "$line" | awk -F' @@ ' '{print $1}')
    file=$(echo "$line" | awk -F' @@ ' '{print $2}')
    old=$(echo "$line" | awk -F' @@ ' '{print $3}')
    new=$(echo "$line" | awk -F' @@ ' '{print $4}')
    tests=$(echo "$line" | awk -F' @@ ' '{print $5}')
    if [ -n "$FILTER" ] && [[ "$name" != *"$FILTER"* ]]; then
        continue
    fi
    pass=${file#"$S"/}
    echo "== $name ($pass)" | tee -a "$LOG"
    cp "$file" "$file.mutate-orig"
    CURRENT=$file
    apply "$file" "$old" "$new"
    if [ $? -ne 0 ]; then
        printf '%s\t%s\t%s\t%s\n' "$pass" "$name" "STALE (text not found)" "-" >> "$OUT"
        restore
        continue
    fi
    args=(--test shaders_validate)
    for t in $tests; do args+=(--test "$t"); done
    if ! cargo test --release -p caustics-gpu "${args[@]}" --no-run >> "$LOG" 2>&1; then
        printf '%s\t%s\t%s\t%s\n' "$pass" "$name" "BUILD FAILED" "-" >> "$OUT"
        restore
        continue
    fi
    # The table's own check fails on purpose while a line is applied: only the shaders are asked.
    if ! cargo test --release -p caustics-gpu --test shaders_validate -- \
        --skip the_mutation_table_names_registered_passes_and_their_text >> "$LOG" 2>&1; then
        printf '%s\t%s\t%s\t%s\n' "$pass" "$name" "INVALID (shader does not validate)" "-" >> "$OUT"
        restore
        continue
    fi
    caught=""
    for t in $tests; do
        tlog=$(mktemp)
        cargo test --release -p caustics-gpu --test "$t" > "$tlog" 2>&1
        cat "$tlog" >> "$LOG"
        for f in $(failed_tests "$tlog"); do caught+="$t::$f "; done
        if grep -q "GPU tests ignored" "$tlog"; then
            caught+="($t: NO DEVICE) "
        fi
        rm -f "$tlog"
    done
    if [ -n "$caught" ]; then
        printf '%s\t%s\t%s\t%s\n' "$pass" "$name" "caught" "$caught" >> "$OUT"
    else
        printf '%s\t%s\t%s\t%s\n' "$pass" "$name" "NOT CAUGHT" "($tests all pass)" >> "$OUT"
    fi
    restore
    tail -1 "$OUT"
done <<< "$MUTATIONS"

echo
column -t -s $'\t' "$OUT"
