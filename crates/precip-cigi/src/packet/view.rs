//! The CIGI 3.3 packets that place the eyepoint: Entity Control (§4.1.2: an
//! entity's geodetic position and attitude, or its offset from a parent), View
//! Control (§4.1.16: a view's offset and rotation from the entity it rides on) and
//! View Definition (§4.1.21: a view's field of view as four half-angles).

use super::Reader;
use crate::error::CigiError;

/// Opcode of Celestial Sphere Control.
pub const CELESTIAL_SPHERE_CONTROL_OPCODE: u8 = 9;
/// Size of Celestial Sphere Control, bytes.
pub const CELESTIAL_SPHERE_CONTROL_SIZE: usize = 16;

/// Celestial Sphere Control (§4.1.9): the time of day and date the IG draws the
/// sky for.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CelestialSphereControl {
    /// Hour, 0–23 (UTC).
    pub hour: u8,
    /// Minute, 0–59.
    pub minute: u8,
    /// The IG places the sun (and moon) from the date and time (ephemeris model).
    pub ephemeris: bool,
    /// The sun is drawn.
    pub sun: bool,
    /// The date field holds a date.
    pub date_valid: bool,
    /// The date as MMDDYYYY.
    pub date: u32,
}

pub(super) fn celestial_sphere_control(r: &Reader<'_>) -> CelestialSphereControl {
    let flags = r.u8(4);
    CelestialSphereControl {
        hour: r.u8(2),
        minute: r.u8(3),
        ephemeris: flags & 0x01 != 0,
        sun: flags & 0x02 != 0,
        date_valid: flags & 0x10 != 0,
        date: r.u32(8),
    }
}

/// Opcode of Entity Control.
pub const ENTITY_CONTROL_OPCODE: u8 = 2;
/// Size of Entity Control, bytes.
pub const ENTITY_CONTROL_SIZE: usize = 48;
/// Opcode of View Control.
pub const VIEW_CONTROL_OPCODE: u8 = 16;
/// Size of View Control, bytes.
pub const VIEW_CONTROL_SIZE: usize = 32;
/// Opcode of View Definition.
pub const VIEW_DEFINITION_OPCODE: u8 = 21;
/// Size of View Definition, bytes.
pub const VIEW_DEFINITION_SIZE: usize = 32;

/// Entity Control: where an entity is and how it is turned.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EntityControl {
    /// The entity (0: the ownship, whose eyepoint the IG draws by default).
    pub entity_id: u16,
    /// 0 inactive/standby, 1 active, 2 destroyed.
    pub entity_state: u8,
    /// Attached to `parent_id`: the position is an offset in the parent's body
    /// axes (x forward, y right, z down, m), not a geodetic one.
    pub attached: bool,
    /// The entity's type (IG-defined).
    pub entity_type: u16,
    /// The parent, when attached.
    pub parent_id: u16,
    /// Roll, degrees (right wing down positive).
    pub roll_deg: f32,
    /// Pitch, degrees (nose up positive).
    pub pitch_deg: f32,
    /// Yaw (heading), degrees clockwise from true north.
    pub yaw_deg: f32,
    /// Latitude, degrees (attached: x offset, m).
    pub latitude_deg_or_x_m: f64,
    /// Longitude, degrees (attached: y offset, m).
    pub longitude_deg_or_y_m: f64,
    /// Altitude above the ellipsoid (WGS 84), m (attached: z offset, m).
    pub altitude_m_or_z_m: f64,
}

/// View Control: a view's place and turn relative to the entity it rides on; only
/// the enabled fields apply.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ViewControl {
    /// The view.
    pub view_id: u16,
    /// Its group.
    pub group_id: u8,
    /// Which of x, y, z, roll, pitch, yaw apply (in that order).
    pub enabled: [bool; 6],
    /// The entity it rides on.
    pub entity_id: u16,
    /// Offsets along the entity's body axes (x forward, y right, z down), m, and
    /// roll, pitch, yaw from its attitude, degrees.
    pub offsets: [f32; 6],
}

/// View Definition: a view's field of view as half-angles from its axis, degrees
/// (left and bottom negative), and its near and far planes, m; only the enabled
/// fields apply.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ViewDefinition {
    /// The view.
    pub view_id: u16,
    /// Its group.
    pub group_id: u8,
    /// Which of near, far, left, right, top, bottom apply (in that order).
    pub enabled: [bool; 6],
    /// Near, far (m), left, right, top, bottom (degrees).
    pub values: [f32; 6],
}

fn bits6(byte: u8) -> [bool; 6] {
    std::array::from_fn(|i| byte & (1 << i) != 0)
}

/// The six 32-bit floats from byte 8 on (View Control's and View Definition's).
fn six_floats(r: &Reader<'_>, fields: [&'static str; 6]) -> Result<[f32; 6], CigiError> {
    let mut values = [0.0f32; 6];
    for (i, (v, field)) in values.iter_mut().zip(fields).enumerate() {
        *v = r.f32(8 + 4 * i, field)?;
    }
    Ok(values)
}

fn f64_field(r: &Reader<'_>, at: usize, field: &'static str) -> Result<f64, CigiError> {
    let bits = r.array::<8>(at);
    let v = f64::from_bits(match r.order {
        super::ByteOrder::Big => u64::from_be_bytes(bits),
        super::ByteOrder::Little => u64::from_le_bytes(bits),
    });
    if v.is_finite() {
        Ok(v)
    } else {
        Err(CigiError::NonFinite { field })
    }
}

pub(super) fn entity_control(r: &Reader<'_>) -> Result<EntityControl, CigiError> {
    let state = r.u8(4);
    Ok(EntityControl {
        entity_id: r.u16(2),
        entity_state: state & 0b11,
        attached: state & 0b100 != 0,
        entity_type: r.u16(8),
        parent_id: r.u16(10),
        roll_deg: r.f32(12, "entity roll")?,
        pitch_deg: r.f32(16, "entity pitch")?,
        yaw_deg: r.f32(20, "entity yaw")?,
        latitude_deg_or_x_m: f64_field(r, 24, "entity latitude")?,
        longitude_deg_or_y_m: f64_field(r, 32, "entity longitude")?,
        altitude_m_or_z_m: f64_field(r, 40, "entity altitude")?,
    })
}

pub(super) fn view_control(r: &Reader<'_>) -> Result<ViewControl, CigiError> {
    const FIELDS: [&str; 6] = [
        "view x offset",
        "view y offset",
        "view z offset",
        "view roll",
        "view pitch",
        "view yaw",
    ];
    Ok(ViewControl {
        view_id: r.u16(2),
        group_id: r.u8(4),
        enabled: bits6(r.u8(5)),
        entity_id: r.u16(6),
        offsets: six_floats(r, FIELDS)?,
    })
}

pub(super) fn view_definition(r: &Reader<'_>) -> Result<ViewDefinition, CigiError> {
    const FIELDS: [&str; 6] = [
        "view near plane",
        "view far plane",
        "view left half-angle",
        "view right half-angle",
        "view top half-angle",
        "view bottom half-angle",
    ];
    Ok(ViewDefinition {
        view_id: r.u16(2),
        group_id: r.u8(4),
        enabled: bits6(r.u8(5)),
        values: six_floats(r, FIELDS)?,
    })
}
