//! [`CigiReceiver`]: host messages from a UDP port, read without blocking once a
//! frame.

use std::collections::BTreeMap;
use std::net::{SocketAddr, UdpSocket};

use precip_model::Weather;

use crate::error::CigiError;
use crate::host_view::{Eyepoint, GeodeticOrigin, HostView};
use crate::host_weather::{Applied, HostWeather};
use crate::packet::{ByteOrder, IgControl, Packet, StartOfFrame, parse_message};

/// What the receiver has seen.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct PacketCounts {
    /// Datagrams read.
    pub datagrams: u64,
    /// Datagrams skipped as malformed (short, unknown order, bad sizes, …).
    pub malformed: u64,
    /// IG Control packets.
    pub ig_control: u64,
    /// Weather Control packets that changed the weather.
    pub weather_applied: u64,
    /// Weather Control packets for layers or scopes precip does not draw.
    pub weather_ignored: u64,
    /// Weather Control packets asking for weather that is not physical.
    pub weather_refused: u64,
    /// Entity Control packets that placed an entity.
    pub entity_control: u64,
    /// View Control and View Definition packets taken for the view drawn.
    pub view_control: u64,
    /// Celestial Sphere Control packets that placed the sun.
    pub celestial: u64,
    /// Entity, View Control, View Definition and Celestial Sphere Control packets
    /// not used (another view, a standby entity, an unknown parent, a field of view
    /// that is none, no ephemeris or date).
    pub view_ignored: u64,
    /// Other packets, skipped by their size ([`CigiReceiver::other_opcodes`]).
    pub other: u64,
    /// Start of Frame packets sent to the host.
    pub start_of_frame_sent: u64,
}

/// The most datagrams read in one [`CigiReceiver::poll`], so a flooding host cannot
/// stall a frame.
pub const MAX_DATAGRAMS_PER_POLL: usize = 256;

/// Reads a host's CIGI messages from a UDP port.
#[derive(Debug)]
pub struct CigiReceiver {
    socket: UdpSocket,
    weather: HostWeather,
    counts: PacketCounts,
    last_error: Option<CigiError>,
    buffer: Vec<u8>,
    /// The weather [`CigiReceiver::poll`] last returned (or started from).
    announced: Weather,
    /// The ground fog [`CigiReceiver::take_fog_layer`] last returned (none at first).
    announced_fog: Option<precip_model::drawing::fog_layer::FogLayer>,
    /// A ground fog that differs from the announced one, not yet taken.
    fog_news: Option<Option<precip_model::drawing::fog_layer::FogLayer>>,
    /// The cloud layers [`CigiReceiver::take_cloud_layers`] last returned.
    announced_clouds: precip_model::drawing::clouds::CloudLayers,
    /// Cloud layers that differ from the announced ones, not yet taken.
    cloud_news: Option<precip_model::drawing::clouds::CloudLayers>,
    /// Where Start of Frame goes: set by [`CigiReceiver::reply_to`], else the sender
    /// of the last well-formed message.
    host: Option<SocketAddr>,
    /// Whether `host` was given (not learnt).
    host_fixed: bool,
    /// The host's last IG Control.
    last_control: Option<IgControl>,
    /// The entities and views the host set.
    view: HostView,
    /// An entity or view changed since [`CigiReceiver::take_eyepoint`].
    view_news: bool,
    /// Packets skipped, by opcode.
    other_opcodes: BTreeMap<u8, u64>,
    /// The host frame [`CigiReceiver::wait_for_host_frame`] last returned.
    waited_host_frame: Option<u32>,
    /// The sun a Celestial Sphere Control placed, not yet taken.
    sun_news: Option<glam::Vec3>,
    /// The sun last taken.
    announced_sun: Option<glam::Vec3>,
}

impl CigiReceiver {
    /// Listens on `port` of every interface (0: a free port), starting from
    /// `weather`.
    pub fn bind(port: u16, weather: Weather) -> Result<Self, CigiError> {
        let socket = UdpSocket::bind(("0.0.0.0", port))
            .map_err(|e| CigiError::Socket(format!("cannot listen on UDP port {port}: {e}")))?;
        socket
            .set_nonblocking(true)
            .map_err(|e| CigiError::Socket(e.to_string()))?;
        Ok(Self {
            socket,
            weather: HostWeather::new(weather),
            counts: PacketCounts::default(),
            last_error: None,
            buffer: vec![0u8; 65_536],
            announced: weather,
            announced_fog: None,
            fog_news: None,
            announced_clouds: precip_model::drawing::clouds::CloudLayers::NONE,
            cloud_news: None,
            host: None,
            host_fixed: false,
            last_control: None,
            view: HostView::new(GeodeticOrigin::default(), 0),
            view_news: false,
            other_opcodes: BTreeMap::new(),
            waited_host_frame: None,
            sun_news: None,
            announced_sun: None,
        })
    }

    /// Draws view `view_id` on the tangent plane at `origin` (before any message:
    /// what the host placed so far is forgotten).
    pub fn set_view(&mut self, origin: GeodeticOrigin, view_id: u16) {
        self.view = HostView::new(origin, view_id);
        self.view_news = false;
    }

    /// Where the host put the view drawn, if an entity or view changed since the
    /// last call and the view's entity is placed; `aspect` is the image's width over
    /// its height ([`HostView::eyepoint`]). Read after [`CigiReceiver::poll`].
    pub fn take_eyepoint(&mut self, aspect: f32) -> Option<Eyepoint> {
        if !std::mem::take(&mut self.view_news) {
            return None;
        }
        self.view.eyepoint(aspect)
    }

    /// Toward the sun, if a Celestial Sphere Control moved it since the last call
    /// (its date and time at the scene's origin); read after [`CigiReceiver::poll`].
    pub fn take_sun(&mut self) -> Option<glam::Vec3> {
        let sun = self.sun_news.take()?;
        self.announced_sun = Some(sun);
        Some(sun)
    }

    /// Packets skipped, by opcode, and how many of each.
    #[must_use]
    pub fn other_opcodes(&self) -> &BTreeMap<u8, u64> {
        &self.other_opcodes
    }

    /// Lockstep with a host running synchronously: polls until a message with a
    /// host frame counter other than the last one waited for arrives (true), or
    /// `timeout` passes (false). Each IG frame then draws one host frame.
    pub fn wait_for_host_frame(&mut self, timeout: std::time::Duration) -> bool {
        let start = std::time::Instant::now();
        loop {
            self.poll_datagrams();
            let frame = self.last_control.map(|c| c.host_frame);
            if frame.is_some() && frame != self.waited_host_frame {
                self.waited_host_frame = frame;
                return true;
            }
            if start.elapsed() >= timeout {
                return false;
            }
            std::thread::sleep(std::time::Duration::from_micros(500));
        }
    }

    /// Sends Start of Frame to `host` (a host that listens on another port than it
    /// sends from); by default it goes to the sender of the last message.
    pub fn reply_to(&mut self, host: SocketAddr) {
        self.host = Some(host);
        self.host_fixed = true;
    }

    /// Tells the host the IG began frame `ig_frame`, `since_start` after it started:
    /// a Start of Frame in the host's byte order, echoing its database, IG mode and
    /// last frame counter. Nothing is sent before a host has been heard (or given);
    /// a failed send is kept as [`CigiReceiver::last_error`], never fatal.
    pub fn send_start_of_frame(&mut self, ig_frame: u32, since_start: std::time::Duration) -> bool {
        let Some(host) = self.host else {
            return false;
        };
        let control = self.last_control;
        let packet = StartOfFrame {
            database: control.map_or(0, |c| c.database),
            ig_status: 0,
            ig_mode: control.map_or(1, |c| c.ig_mode),
            ig_frame,
            // 10 µs ticks, wrapping as the ICD's 32-bit counter does.
            timestamp_10us: (since_start.as_micros() / 10) as u32,
            last_host_frame: control.map_or(0, |c| c.host_frame),
        };
        let order = control.map_or(ByteOrder::Big, |c| c.byte_order);
        match self.socket.send_to(&packet.to_bytes(order), host) {
            Ok(_) => {
                self.counts.start_of_frame_sent += 1;
                true
            }
            Err(e) => {
                self.last_error = Some(CigiError::Socket(format!(
                    "sending Start of Frame to {host}: {e}"
                )));
                false
            }
        }
    }

    /// The address it listens on.
    pub fn local_addr(&self) -> Result<SocketAddr, CigiError> {
        self.socket
            .local_addr()
            .map_err(|e| CigiError::Socket(e.to_string()))
    }

    /// Reads the datagrams waiting (at most [`MAX_DATAGRAMS_PER_POLL`]); returns
    /// the weather if they changed it since the last time it returned one.
    pub fn poll(&mut self) -> Option<Weather> {
        self.poll_datagrams();
        let news = self.announced != self.weather.weather();
        self.announced = self.weather.weather();
        news.then_some(self.announced)
    }

    /// Reads the datagrams waiting (at most [`MAX_DATAGRAMS_PER_POLL`]).
    fn poll_datagrams(&mut self) {
        for _ in 0..MAX_DATAGRAMS_PER_POLL {
            let Ok((len, sender)) = self.socket.recv_from(&mut self.buffer) else {
                break;
            };
            self.counts.datagrams += 1;
            let datagram = self.buffer.get(..len).unwrap_or_default();
            match parse_message(datagram) {
                Ok(packets) => {
                    if !self.host_fixed {
                        self.host = Some(sender);
                    }
                    for packet in packets {
                        self.take(&packet);
                    }
                }
                Err(e) => {
                    self.counts.malformed += 1;
                    self.last_error = Some(e);
                }
            }
        }
    }

    fn take(&mut self, packet: &Packet) {
        match packet {
            Packet::IgControl(c) => {
                self.counts.ig_control += 1;
                self.last_control = Some(*c);
            }
            Packet::Other { opcode } => {
                self.counts.other += 1;
                *self.other_opcodes.entry(*opcode).or_default() += 1;
            }
            Packet::CelestialSphereControl(c) => match self.view.sun(c) {
                Some(sun) => {
                    self.counts.celestial += 1;
                    self.sun_news = (Some(sun) != self.announced_sun).then_some(sun);
                }
                None => self.counts.view_ignored += 1,
            },
            Packet::EntityControl(e) => {
                let placed = self.view.apply_entity(e);
                self.count_view(placed, true);
            }
            Packet::ViewControl(v) => {
                let taken = self.view.apply_view_control(v);
                self.count_view(taken, false);
            }
            Packet::ViewDefinition(v) => {
                let taken = self.view.apply_view_definition(v);
                self.count_view(taken, false);
            }
            Packet::WeatherControl(w) => match self.weather.apply(w) {
                // A host repeats its weather every frame: only a change is news
                // (poll compares it with the one announced).
                Applied::Changed(_) => self.counts.weather_applied += 1,
                Applied::Fog(fog) => {
                    self.counts.weather_applied += 1;
                    self.fog_news = (fog != self.announced_fog).then_some(fog);
                }
                Applied::Clouds(clouds) => {
                    self.counts.weather_applied += 1;
                    self.cloud_news = (clouds != self.announced_clouds).then_some(clouds);
                }
                Applied::Ignored => self.counts.weather_ignored += 1,
                Applied::Refused => self.counts.weather_refused += 1,
            },
        }
    }

    /// Counts an entity (`entity`) or view packet taken or not; one taken is news
    /// for [`CigiReceiver::take_eyepoint`].
    fn count_view(&mut self, taken: bool, entity: bool) {
        match (taken, entity) {
            (true, true) => self.counts.entity_control += 1,
            (true, false) => self.counts.view_control += 1,
            (false, _) => self.counts.view_ignored += 1,
        }
        self.view_news |= taken;
    }

    /// The ground fog the host set since the last call, if it changed (`Some(None)`:
    /// it was cleared); read after [`CigiReceiver::poll`].
    pub fn take_fog_layer(&mut self) -> Option<Option<precip_model::drawing::fog_layer::FogLayer>> {
        let news = self.fog_news.take()?;
        self.announced_fog = news;
        Some(news)
    }

    /// The cloud layers the host set since the last call, if they changed (empty:
    /// every layer is off); read after [`CigiReceiver::poll`].
    pub fn take_cloud_layers(&mut self) -> Option<precip_model::drawing::clouds::CloudLayers> {
        let news = self.cloud_news.take()?;
        self.announced_clouds = news;
        Some(news)
    }

    /// The weather in effect.
    #[must_use]
    pub fn weather(&self) -> Weather {
        self.weather.weather()
    }

    /// What it has seen.
    #[must_use]
    pub fn counts(&self) -> PacketCounts {
        self.counts
    }

    /// Why the last malformed datagram was skipped.
    #[must_use]
    pub fn last_error(&self) -> Option<&CigiError> {
        self.last_error.as_ref()
    }
}
