//! [`CigiError`]: why a datagram was skipped.

/// What was wrong with a datagram (it is counted and skipped, never a panic).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum CigiError {
    /// Fewer bytes than a packet needs.
    #[error("CIGI message truncated at byte {offset}: needs {needed} bytes, {available} left")]
    Truncated {
        /// Where the packet starts.
        offset: usize,
        /// Bytes it needs.
        needed: usize,
        /// Bytes there are.
        available: usize,
    },
    /// A message must start with IG Control.
    #[error(
        "CIGI message starts with opcode {opcode}, not IG Control (1): the host must send IG Control first"
    )]
    NotIgControlFirst {
        /// The first opcode.
        opcode: u8,
    },
    /// Not CIGI 3.
    #[error("CIGI major version {major_version} is not supported: precip reads CIGI 3.x (3.3)")]
    UnsupportedVersion {
        /// The version sent.
        major_version: u8,
    },
    /// The byte-swap magic number is neither order of 0x8000.
    #[error("CIGI byte-swap magic number {magic:#06x} is neither 0x8000 nor 0x0080")]
    BadMagic {
        /// The number read big-endian.
        magic: u16,
    },
    /// A packet's size is impossible or not its opcode's.
    #[error("CIGI packet with opcode {opcode} has size {size} (expected {expected:?})")]
    BadSize {
        /// Its opcode.
        opcode: u8,
        /// Its size byte.
        size: usize,
        /// The size its opcode has, when precip reads it.
        expected: Option<usize>,
    },
    /// A number is NaN or infinite.
    #[error("CIGI field {field} is not finite")]
    NonFinite {
        /// The field.
        field: &'static str,
    },
    /// The socket failed.
    #[error("CIGI socket: {0}")]
    Socket(String),
}
