//! The run-once path, for tools and tests that need numbers: a frame built for one height grid,
//! its passes in one submission, and the map (or the region it chose) read back.

use caustics_core::grid::Grid;
use caustics_core::map::CausticsMap;
use caustics_core::techniques::yuksel::{Region, YukselSetup};

use super::{Frame, Variant, Yuksel, YukselRegion};
use crate::{GpuContext, GpuError, GpuTimer};

impl Yuksel {
    /// The region the last encode of `frame` chose, read back (for tests and tools: it waits for
    /// the GPU).
    pub fn read_region(&self, ctx: &GpuContext, frame: &Frame) -> Result<Region, GpuError> {
        let r: Vec<YukselRegion> = ctx.read_buffer(&frame.region)?;
        Ok(r[0].into())
    }

    /// Run the technique once and read the map back, writing each pass's timestamps into `timer`
    /// when there is one (resolved in the same submission; read them with [`GpuTimer::read`]).
    pub fn caustics(
        &self,
        ctx: &GpuContext,
        setup: &YukselSetup,
        heights: &Grid,
        variant: Variant,
        mut timer: Option<&mut GpuTimer>,
    ) -> Result<CausticsMap, GpuError> {
        let frame = self.frame(ctx, setup, heights, variant)?;
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        let texture = self.encode(&frame, &mut encoder, timer.as_deref_mut());
        ctx.submit_timed(encoder, timer.as_deref());
        ctx.read_map(texture, setup.size)
    }
}
