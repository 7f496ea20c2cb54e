// What both passes of the water's slope moments' pyramid read about the level they write
// (`water_slopes_base.wgsl`, `water_slopes_halve.wgsl`).

// Mirrors `SlopeLevelUniform` in crates/gpu/src/final_image/slopes.rs.
struct SlopeLevel {
    // The water square's side.
    size: f32,
    // The water's edge rule (1: periodic).
    wrap: u32,
    // Where this level's texels start in `moments`, in texels, and its columns and rows.
    offset: u32,
    cols: u32,
    rows: u32,
    // The level below's (unused at level 0).
    below_offset: u32,
    below_cols: u32,
    below_rows: u32,
}
