struct SlopeLevel {
    size: f32,
    wrap: u32,
    offset: u32,
    cols: u32,
    rows: u32,
    below_offset: u32,
    below_cols: u32,
    below_rows: u32
}
