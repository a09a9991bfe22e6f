//! Streaming the image to the tev viewer (`render --tev HOST:PORT`) over its TCP protocol, through
//! the `tev_client` crate: one RGB image is created, then updated as the render progresses. A viewer
//! that goes away only ends the streaming, never the render.
use crate::output::film::Film;
use anyhow::{Context, Result};
use std::net::{TcpStream, ToSocketAddrs};
use std::time::Duration;
use tev_client::{PacketCreateImage, PacketUpdateImage, TevClient};

const CHANNELS: [&str; 3] = ["R", "G", "B"];

pub struct TevStream {
    client: TevClient,
    name: String,
    width: u32,
    height: u32,
}

impl TevStream {
    /// Connects to tev at `address` and creates the image `name` of `width` × `height`.
    pub fn connect(address: &str, name: &str, width: u32, height: u32) -> Result<TevStream> {
        let target = address
            .to_socket_addrs()
            .with_context(|| format!("--tev {address}: not a host:port"))?
            .next()
            .with_context(|| format!("--tev {address}: no address"))?;
        let socket = TcpStream::connect_timeout(&target, Duration::from_secs(3))
            .with_context(|| format!("cannot reach tev at {address} (is `tev` running?)"))?;
        // A viewer that accepts the connection and never reads would block the render for good: a
        // write that waits this long fails, and the render carries on without the viewer.
        socket
            .set_write_timeout(Some(Duration::from_secs(5)))
            .with_context(|| format!("tev at {address}: cannot set a write timeout"))?;
        let mut client = TevClient::wrap(socket);
        // tev_client asserts on empty images; the film is never empty, but say so here too.
        anyhow::ensure!(width > 0 && height > 0, "an empty image cannot be streamed");
        client
            .send(PacketCreateImage {
                image_name: name,
                grab_focus: true,
                width,
                height,
                channel_names: &CHANNELS,
            })
            .with_context(|| format!("tev at {address} closed the connection"))?;
        Ok(TevStream { client, name: name.to_string(), width, height })
    }

    /// Sends the whole image (non-finite values as 0, as in the saved image).
    pub fn update(&mut self, film: &Film) -> Result<()> {
        let data: Vec<f32> =
            film.rgb.iter().flatten().map(|&c| if c.is_finite() { c } else { 0.0 }).collect();
        self.client
            .send(PacketUpdateImage {
                image_name: &self.name,
                grab_focus: false,
                channel_names: &CHANNELS,
                channel_offsets: &[0, 1, 2],
                channel_strides: &[3, 3, 3],
                x: 0,
                y: 0,
                width: self.width,
                height: self.height,
                data: &data,
            })
            .context("tev closed the connection")
    }
}
