//! Reading a GPU buffer back: a slice of a `MAP_READ` buffer mapped, waited for and copied out, for
//! the backend's readbacks and the step times' timestamps alike.
use anyhow::{anyhow, Result};

/// The bytes of `slice` (of a buffer with `MAP_READ`, whose copy into it is submitted), once the
/// device has finished; the buffer is unmapped again. `what` names it in errors.
pub fn map_read(device: &wgpu::Device, slice: wgpu::BufferSlice<'_>, what: &str) -> Result<Vec<u8>> {
    let (tx, rx) = std::sync::mpsc::channel();
    slice.map_async(wgpu::MapMode::Read, move |r| {
        let _ = tx.send(r);
    });
    device.poll(wgpu::PollType::wait_indefinitely()).map_err(|e| anyhow!("GPU wait failed: {e}"))?;
    rx.recv()
        .map_err(|_| anyhow!("the readback of {what} was dropped"))?
        .map_err(|e| anyhow!("cannot map {what}: {e}"))?;
    let data = {
        let view = slice.get_mapped_range().map_err(|e| anyhow!("cannot read {what}: {e:?}"))?;
        view.to_vec()
    };
    slice.buffer().unmap();
    Ok(data)
}
