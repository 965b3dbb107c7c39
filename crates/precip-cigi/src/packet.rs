//! The CIGI 3.3 packets precip reads, parsed from a datagram (a CIGI message).
//!
//! A host's message starts with IG Control (opcode 1, 24 bytes), whose byte-swap
//! magic number (bytes 6–7, 0x8000 in the sender's order) says the message's byte
//! order: read big-endian it is 0x8000 for a big-endian sender and 0x0080 for a
//! little-endian one. Every packet starts with its opcode and its size in bytes;
//! packets precip does not use are skipped by their size. Layouts: CIGI ICD 3.3,
//! §4.1.1 (IG Control), §4.1.12 (Weather Control), and for the eyepoint §4.1.2
//! (Entity Control), §4.1.16 (View Control), §4.1.21 (View Definition) in
//! `view`.
//!
//! The IG answers each frame with Start of Frame (§4.2.1, opcode 101, 24 bytes:
//! major version, database, IG status, IG mode / timestamp valid / earth model /
//! minor version, the magic number, the IG's frame counter, a timestamp in 10 µs
//! ticks, the last host frame received), which [`StartOfFrame::to_bytes`] writes in
//! the host's byte order; IG-to-host messages start with it as host messages start
//! with IG Control, so [`parse_start_of_frame`] reads one back.

use crate::error::CigiError;

mod view;
pub use view::{
    CELESTIAL_SPHERE_CONTROL_OPCODE, CELESTIAL_SPHERE_CONTROL_SIZE, CelestialSphereControl,
    ENTITY_CONTROL_OPCODE, ENTITY_CONTROL_SIZE, EntityControl, VIEW_CONTROL_OPCODE,
    VIEW_CONTROL_SIZE, VIEW_DEFINITION_OPCODE, VIEW_DEFINITION_SIZE, ViewControl, ViewDefinition,
};

/// Opcode of IG Control.
pub const IG_CONTROL_OPCODE: u8 = 1;
/// Size of IG Control, bytes.
pub const IG_CONTROL_SIZE: usize = 24;
/// Opcode of Weather Control.
pub const WEATHER_CONTROL_OPCODE: u8 = 12;
/// Size of Weather Control, bytes.
pub const WEATHER_CONTROL_SIZE: usize = 56;
/// Opcode of Start of Frame (IG to host).
pub const START_OF_FRAME_OPCODE: u8 = 101;
/// Size of Start of Frame, bytes.
pub const START_OF_FRAME_SIZE: usize = 24;
/// The magic number as a big-endian sender writes it.
pub const BYTE_SWAP_MAGIC: u16 = 0x8000;

/// The byte order of a message.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ByteOrder {
    /// Most significant byte first.
    Big,
    /// Least significant byte first.
    Little,
}

/// IG Control: the message's header.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct IgControl {
    /// CIGI major version (3).
    pub major_version: u8,
    /// CIGI minor version (3 for 3.3).
    pub minor_version: u8,
    /// Database number the host asks for.
    pub database: i8,
    /// IG mode: 0 reset/standby, 1 operate, 2 debug, 3 offline maintenance.
    pub ig_mode: u8,
    /// The host's frame counter.
    pub host_frame: u32,
    /// The last IG frame the host received.
    pub last_ig_frame: u32,
    /// The message's byte order (from the magic number).
    pub byte_order: ByteOrder,
}

/// Weather Control (global, regional or entity scope).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WeatherControl {
    /// Entity or region the packet is for (unused for the global scope).
    pub entity_region_id: u16,
    /// Layer: 0 ground fog, 1–3 clouds, 4 rain, 5 snow, 6 sleet, 7 hail, 8 sand,
    /// 9 dust, 10–255 IG-defined.
    pub layer: u8,
    /// Relative humidity, %.
    pub humidity_percent: u8,
    /// Whether the layer is on.
    pub enabled: bool,
    /// Whether the IG may vary the wind.
    pub random_winds: bool,
    /// Cloud type of a cloud layer: 0 none, 1 altocumulus, 2 altostratus, 3
    /// cirrocumulus, 4 cirrostratus, 5 cirrus, 6 cumulonimbus, 7 cumulus, 8
    /// nimbostratus, 9 stratocumulus, 10 stratus, 11–15 other.
    pub cloud_type: u8,
    /// Scope: 0 global, 1 regional, 2 entity.
    pub scope: u8,
    /// Severity, 0 (least) to 5 (most severe).
    pub severity: u8,
    /// Air temperature, °C.
    pub air_temperature_c: f32,
    /// Visibility range, m.
    pub visibility_m: f32,
    /// Coverage of the layer, %.
    pub coverage_percent: f32,
    /// Base elevation of the layer, m.
    pub base_elevation_m: f32,
    /// Thickness of the layer, m.
    pub thickness_m: f32,
    /// Height of the band above and below the layer over which its visibility
    /// turns into the air's around it, m.
    pub transition_band_m: f32,
    /// Horizontal wind speed, m/s.
    pub horizontal_wind_mps: f32,
    /// Vertical wind speed, m/s (up positive).
    pub vertical_wind_mps: f32,
    /// Direction the wind blows from, degrees clockwise from true north.
    pub wind_from_deg: f32,
}

/// Start of Frame: what the IG tells the host each frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct StartOfFrame {
    /// The database the IG has loaded (the host's request, echoed).
    pub database: i8,
    /// IG status: 0 normal.
    pub ig_status: u8,
    /// IG mode: 0 reset/standby, 1 operate, 2 debug, 3 offline maintenance.
    pub ig_mode: u8,
    /// The IG's frame counter.
    pub ig_frame: u32,
    /// Time since the IG started, 10 µs ticks (wrapping).
    pub timestamp_10us: u32,
    /// The last host frame the IG received (IG Control's frame counter).
    pub last_host_frame: u32,
}

impl StartOfFrame {
    /// The packet's 24 bytes in `order` (CIGI 3.3, timestamp valid, WGS 84).
    #[must_use]
    pub fn to_bytes(&self, order: ByteOrder) -> [u8; START_OF_FRAME_SIZE] {
        let mut out = [0u8; START_OF_FRAME_SIZE];
        out[0] = START_OF_FRAME_OPCODE;
        out[1] = START_OF_FRAME_SIZE as u8;
        out[2] = 3;
        out[3] = self.database.to_ne_bytes()[0];
        out[4] = self.ig_status;
        // Minor version 3 in bits 4–7, timestamp valid (bit 2), IG mode (bits 0–1).
        out[5] = (3 << 4) | 0x04 | (self.ig_mode & 0b11);
        let put16 = |v: u16| match order {
            ByteOrder::Big => v.to_be_bytes(),
            ByteOrder::Little => v.to_le_bytes(),
        };
        let put32 = |v: u32| match order {
            ByteOrder::Big => v.to_be_bytes(),
            ByteOrder::Little => v.to_le_bytes(),
        };
        out[6..8].copy_from_slice(&put16(BYTE_SWAP_MAGIC));
        out[8..12].copy_from_slice(&put32(self.ig_frame));
        out[12..16].copy_from_slice(&put32(self.timestamp_10us));
        out[16..20].copy_from_slice(&put32(self.last_host_frame));
        out
    }
}

/// Reads a Start of Frame (what a host receives from precip) and its byte order.
pub fn parse_start_of_frame(bytes: &[u8]) -> Result<(StartOfFrame, ByteOrder), CigiError> {
    if bytes.len() < START_OF_FRAME_SIZE {
        return Err(CigiError::Truncated {
            offset: 0,
            needed: START_OF_FRAME_SIZE,
            available: bytes.len(),
        });
    }
    if bytes[0] != START_OF_FRAME_OPCODE || usize::from(bytes[1]) != START_OF_FRAME_SIZE {
        return Err(CigiError::BadSize {
            opcode: bytes[0],
            size: usize::from(bytes[1]),
            expected: Some(START_OF_FRAME_SIZE),
        });
    }
    if bytes[2] != 3 {
        return Err(CigiError::UnsupportedVersion {
            major_version: bytes[2],
        });
    }
    let order = byte_order(bytes)?;
    let r = Reader { bytes, order };
    Ok((
        StartOfFrame {
            database: i8::from_ne_bytes([r.u8(3)]),
            ig_status: r.u8(4),
            ig_mode: r.u8(5) & 0b11,
            ig_frame: r.u32(8),
            timestamp_10us: r.u32(12),
            last_host_frame: r.u32(16),
        },
        order,
    ))
}

/// A packet of a message.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Packet {
    /// IG Control.
    IgControl(IgControl),
    /// Weather Control.
    WeatherControl(WeatherControl),
    /// Entity Control.
    EntityControl(EntityControl),
    /// Celestial Sphere Control.
    CelestialSphereControl(CelestialSphereControl),
    /// View Control.
    ViewControl(ViewControl),
    /// View Definition.
    ViewDefinition(ViewDefinition),
    /// A packet precip does not read (skipped by its size).
    Other {
        /// Its opcode.
        opcode: u8,
    },
}

/// Reads numbers of one byte order from a packet's bytes.
struct Reader<'a> {
    bytes: &'a [u8],
    order: ByteOrder,
}

impl Reader<'_> {
    fn u8(&self, at: usize) -> u8 {
        self.bytes.get(at).copied().unwrap_or(0)
    }

    fn array<const N: usize>(&self, at: usize) -> [u8; N] {
        let mut out = [0u8; N];
        if let Some(src) = self.bytes.get(at..at + N) {
            out.copy_from_slice(src);
        }
        out
    }

    fn u16(&self, at: usize) -> u16 {
        let b = self.array::<2>(at);
        match self.order {
            ByteOrder::Big => u16::from_be_bytes(b),
            ByteOrder::Little => u16::from_le_bytes(b),
        }
    }

    fn u32(&self, at: usize) -> u32 {
        let b = self.array::<4>(at);
        match self.order {
            ByteOrder::Big => u32::from_be_bytes(b),
            ByteOrder::Little => u32::from_le_bytes(b),
        }
    }

    fn f32(&self, at: usize, field: &'static str) -> Result<f32, CigiError> {
        let v = f32::from_bits(self.u32(at));
        if v.is_finite() {
            Ok(v)
        } else {
            Err(CigiError::NonFinite { field })
        }
    }
}

/// The byte order of a message from its IG Control's magic number.
fn byte_order(datagram: &[u8]) -> Result<ByteOrder, CigiError> {
    let magic = datagram
        .get(6..8)
        .map(|b| u16::from_be_bytes([b[0], b[1]]))
        .ok_or(CigiError::Truncated {
            offset: 0,
            needed: IG_CONTROL_SIZE,
            available: datagram.len(),
        })?;
    match magic {
        BYTE_SWAP_MAGIC => Ok(ByteOrder::Big),
        m if m == BYTE_SWAP_MAGIC.swap_bytes() => Ok(ByteOrder::Little),
        other => Err(CigiError::BadMagic { magic: other }),
    }
}

fn ig_control(r: &Reader<'_>, order: ByteOrder) -> Result<IgControl, CigiError> {
    let major_version = r.u8(2);
    if major_version != 3 {
        return Err(CigiError::UnsupportedVersion { major_version });
    }
    let flags = r.u8(4);
    Ok(IgControl {
        major_version,
        minor_version: flags >> 4,
        database: i8::from_ne_bytes([r.u8(3)]),
        ig_mode: flags & 0b11,
        host_frame: r.u32(8),
        last_ig_frame: r.u32(16),
        byte_order: order,
    })
}

fn weather_control(r: &Reader<'_>) -> Result<WeatherControl, CigiError> {
    let flags = r.u8(6);
    let scope_severity = r.u8(7);
    Ok(WeatherControl {
        entity_region_id: r.u16(2),
        layer: r.u8(4),
        humidity_percent: r.u8(5),
        enabled: flags & 0x01 != 0,
        random_winds: flags & 0x04 != 0,
        cloud_type: flags >> 4,
        scope: scope_severity & 0b11,
        severity: (scope_severity >> 2) & 0b111,
        air_temperature_c: r.f32(8, "air temperature")?,
        visibility_m: r.f32(12, "visibility range")?,
        coverage_percent: r.f32(20, "coverage")?,
        base_elevation_m: r.f32(24, "base elevation")?,
        thickness_m: r.f32(28, "thickness")?,
        transition_band_m: r.f32(32, "transition band")?,
        horizontal_wind_mps: r.f32(36, "horizontal wind speed")?,
        vertical_wind_mps: r.f32(40, "vertical wind speed")?,
        wind_from_deg: r.f32(44, "wind direction")?,
    })
}

/// The packets of one message. The first must be IG Control (major version 3); a
/// packet whose size is under 2, runs past the end, or differs from its opcode's
/// size is an error, as is a non-finite number where precip reads one.
pub fn parse_message(datagram: &[u8]) -> Result<Vec<Packet>, CigiError> {
    if datagram.len() < IG_CONTROL_SIZE {
        return Err(CigiError::Truncated {
            offset: 0,
            needed: IG_CONTROL_SIZE,
            available: datagram.len(),
        });
    }
    if datagram[0] != IG_CONTROL_OPCODE {
        return Err(CigiError::NotIgControlFirst {
            opcode: datagram[0],
        });
    }
    let order = byte_order(datagram)?;
    let mut packets = Vec::new();
    let mut offset = 0;
    while offset < datagram.len() {
        let rest = &datagram[offset..];
        let opcode = rest[0];
        let size = usize::from(rest.get(1).copied().unwrap_or(0));
        if size < 2 {
            return Err(CigiError::BadSize {
                opcode,
                size,
                expected: None,
            });
        }
        let Some(bytes) = rest.get(..size) else {
            return Err(CigiError::Truncated {
                offset,
                needed: size,
                available: rest.len(),
            });
        };
        let expected = match opcode {
            IG_CONTROL_OPCODE => Some(IG_CONTROL_SIZE),
            WEATHER_CONTROL_OPCODE => Some(WEATHER_CONTROL_SIZE),
            ENTITY_CONTROL_OPCODE => Some(ENTITY_CONTROL_SIZE),
            CELESTIAL_SPHERE_CONTROL_OPCODE => Some(CELESTIAL_SPHERE_CONTROL_SIZE),
            VIEW_CONTROL_OPCODE => Some(VIEW_CONTROL_SIZE),
            VIEW_DEFINITION_OPCODE => Some(VIEW_DEFINITION_SIZE),
            _ => None,
        };
        if expected.is_some_and(|e| e != size) {
            return Err(CigiError::BadSize {
                opcode,
                size,
                expected,
            });
        }
        let r = Reader { bytes, order };
        packets.push(match opcode {
            IG_CONTROL_OPCODE => Packet::IgControl(ig_control(&r, order)?),
            WEATHER_CONTROL_OPCODE => Packet::WeatherControl(weather_control(&r)?),
            ENTITY_CONTROL_OPCODE => Packet::EntityControl(view::entity_control(&r)?),
            CELESTIAL_SPHERE_CONTROL_OPCODE => {
                Packet::CelestialSphereControl(view::celestial_sphere_control(&r))
            }
            VIEW_CONTROL_OPCODE => Packet::ViewControl(view::view_control(&r)?),
            VIEW_DEFINITION_OPCODE => Packet::ViewDefinition(view::view_definition(&r)?),
            _ => Packet::Other { opcode },
        });
        offset += size;
    }
    Ok(packets)
}
