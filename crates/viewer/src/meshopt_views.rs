//! `EXT_meshopt_compression`: a buffer view whose bytes are meshoptimizer-encoded in
//! another buffer, decoded here with the `meshopt` crate (the bindings of the C++
//! meshoptimizer library that the extension's authors maintain, the reference
//! decoder of the format).
//!
//! The C++ decoder guards its preconditions with `assert` only (an abort in debug
//! builds, nothing in release), so every one is checked first and a file that breaks
//! one is an error naming the view.

use serde_json::Value;

/// Most bytes one decoded view may take (a guard against a hostile `count`).
const MAX_DECODED_BYTES: usize = 1 << 30;

/// The extension object of a view, read.
#[derive(Debug, Clone, PartialEq)]
pub struct MeshoptView {
    /// The buffer holding the encoded bytes.
    pub buffer: usize,
    /// Where they start in it.
    pub byte_offset: usize,
    /// How many there are.
    pub byte_length: usize,
    /// Bytes per decoded element.
    pub byte_stride: usize,
    /// Decoded elements.
    pub count: usize,
    /// `ATTRIBUTES`, `TRIANGLES` or `INDICES`.
    pub mode: String,
    /// `NONE`, `OCTAHEDRAL`, `QUATERNION` or `EXPONENTIAL`.
    pub filter: String,
}

fn field(ext: &Value, name: &str) -> Result<usize, String> {
    ext.get(name)
        .and_then(Value::as_u64)
        .and_then(|v| usize::try_from(v).ok())
        .ok_or_else(|| format!("EXT_meshopt_compression.{name} is missing or not a count"))
}

impl MeshoptView {
    /// Reads the extension object `ext`.
    pub fn parse(ext: &Value) -> Result<Self, String> {
        let text = |name: &str, default: &str| {
            ext.get(name)
                .map_or(Some(default.to_owned()), |v| v.as_str().map(str::to_owned))
                .ok_or_else(|| format!("EXT_meshopt_compression.{name} is not a string"))
        };
        Ok(Self {
            buffer: field(ext, "buffer")?,
            byte_offset: ext
                .get("byteOffset")
                .map_or(Ok(0), |_| field(ext, "byteOffset"))?,
            byte_length: field(ext, "byteLength")?,
            byte_stride: field(ext, "byteStride")?,
            count: field(ext, "count")?,
            mode: text("mode", "")?,
            filter: text("filter", "NONE")?,
        })
    }

    /// Decodes `buffer` (the whole buffer the view's encoded bytes are in).
    pub fn decode(&self, buffer: &[u8]) -> Result<Vec<u8>, String> {
        let encoded = self
            .byte_offset
            .checked_add(self.byte_length)
            .and_then(|end| buffer.get(self.byte_offset..end))
            .ok_or("its encoded bytes reach past their buffer")?;
        let (stride, count) = (self.byte_stride, self.count);
        let bytes = stride
            .checked_mul(count)
            .filter(|&b| b <= MAX_DECODED_BYTES)
            .ok_or("it decodes to more than 1 GiB")?;
        let filter_fits = match self.filter.as_str() {
            "NONE" => true,
            "OCTAHEDRAL" => stride == 4 || stride == 8,
            "QUATERNION" => stride == 8,
            "EXPONENTIAL" => matches!(stride, 4 | 8 | 12 | 16),
            other => return Err(format!("filter {other:?} is not known")),
        };
        if !filter_fits || (self.filter != "NONE" && self.mode != "ATTRIBUTES") {
            return Err(format!(
                "filter {} on {} with a byteStride of {stride}",
                self.filter, self.mode
            ));
        }
        // Decoded into u32 words, so the filters' element types are aligned.
        let mut words = vec![0u32; bytes.div_ceil(4)];
        let status = match self.mode.as_str() {
            "ATTRIBUTES" => {
                if stride == 0 || stride % 4 != 0 || stride > 256 {
                    return Err(format!(
                        "ATTRIBUTES with a byteStride of {stride} (must be a multiple of 4 up to 256)"
                    ));
                }
                ffi::decode_vertex_buffer(&mut words, count, stride, encoded)
            }
            "TRIANGLES" | "INDICES" => {
                if stride != 2 && stride != 4 {
                    return Err(format!(
                        "{} with a byteStride of {stride} (must be 2 or 4)",
                        self.mode
                    ));
                }
                if self.mode == "TRIANGLES" && count % 3 != 0 {
                    return Err(format!(
                        "TRIANGLES with {count} indices (not a multiple of 3)"
                    ));
                }
                ffi::decode_indices(&mut words, count, stride, encoded, self.mode == "TRIANGLES")
            }
            other => {
                return Err(format!(
                    "mode {other:?} is not ATTRIBUTES, TRIANGLES or INDICES"
                ));
            }
        };
        if status != 0 {
            return Err(format!(
                "meshoptimizer could not decode it (status {status})"
            ));
        }
        self.unfilter(&mut words)?;
        let mut out: Vec<u8> = bytemuck::cast_slice(&words).to_vec();
        out.truncate(bytes);
        Ok(out)
    }

    /// Undoes the view's filter in place.
    fn unfilter(&self, words: &mut [u32]) -> Result<(), String> {
        let stride = self.byte_stride;
        let wrong = || format!("filter {} with a byteStride of {stride}", self.filter);
        match (self.filter.as_str(), stride) {
            ("NONE", _) => {}
            ("OCTAHEDRAL", 4) => meshopt::decode_filter_oct::<i8>(bytemuck::cast_slice_mut(words)),
            ("OCTAHEDRAL", 8) => meshopt::decode_filter_oct::<i16>(bytemuck::cast_slice_mut(words)),
            ("QUATERNION", 8) => meshopt::decode_filter_quat(bytemuck::cast_slice_mut(words)),
            ("EXPONENTIAL", 4) => meshopt::decode_filter_exp::<1>(bytemuck::cast_slice_mut(words)),
            ("EXPONENTIAL", 8) => meshopt::decode_filter_exp::<2>(bytemuck::cast_slice_mut(words)),
            ("EXPONENTIAL", 12) => meshopt::decode_filter_exp::<3>(bytemuck::cast_slice_mut(words)),
            ("EXPONENTIAL", 16) => meshopt::decode_filter_exp::<4>(bytemuck::cast_slice_mut(words)),
            ("OCTAHEDRAL" | "QUATERNION" | "EXPONENTIAL", _) => return Err(wrong()),
            (other, _) => return Err(format!("filter {other:?} is not known")),
        }
        Ok(())
    }
}

/// The two decoders the safe wrapper offers only for a fixed element type.
#[expect(
    unsafe_code,
    reason = "meshoptimizer's C decoders for a stride known only at run time"
)]
mod ffi {
    /// Decodes `count` vertices of `stride` bytes into `out` (at least count × stride
    /// bytes); 0 on success.
    pub fn decode_vertex_buffer(
        out: &mut [u32],
        count: usize,
        stride: usize,
        encoded: &[u8],
    ) -> i32 {
        if out.len() * 4 < count * stride {
            return -1;
        }
        // SAFETY: `out` holds count × stride bytes (checked above); `encoded` is a live
        // slice of its stated length; the stride satisfies the decoder's asserts
        // (checked by the caller: a multiple of 4 in 4..=256).
        unsafe {
            meshopt::ffi::meshopt_decodeVertexBuffer(
                out.as_mut_ptr().cast(),
                count,
                stride,
                encoded.as_ptr(),
                encoded.len(),
            )
        }
    }

    /// Decodes `count` indices of `stride` (2 or 4) bytes, a triangle list or a
    /// sequence; 0 on success.
    pub fn decode_indices(
        out: &mut [u32],
        count: usize,
        stride: usize,
        encoded: &[u8],
        triangles: bool,
    ) -> i32 {
        if out.len() * 4 < count * stride {
            return -1;
        }
        // SAFETY: as above; the caller checked stride ∈ {2, 4} and, for triangles, a
        // count that is a multiple of 3.
        unsafe {
            if triangles {
                meshopt::ffi::meshopt_decodeIndexBuffer(
                    out.as_mut_ptr().cast(),
                    count,
                    stride,
                    encoded.as_ptr(),
                    encoded.len(),
                )
            } else {
                meshopt::ffi::meshopt_decodeIndexSequence(
                    out.as_mut_ptr().cast(),
                    count,
                    stride,
                    encoded.as_ptr(),
                    encoded.len(),
                )
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn broken_extension_objects_are_refused_before_the_decoder() {
        let ok = json!({ "buffer": 0, "byteLength": 8, "byteStride": 4, "count": 2, "mode": "ATTRIBUTES" });
        let view = MeshoptView::parse(&ok).expect("parses");
        assert!(
            view.decode(&[0; 4])
                .unwrap_err()
                .contains("past their buffer")
        );
        for (patch, wanted) in [
            (json!({ "byteStride": 6 }), "multiple of 4"),
            (json!({ "byteStride": 0 }), "multiple of 4"),
            (
                json!({ "mode": "TRIANGLES", "byteStride": 2, "count": 4 }),
                "multiple of 3",
            ),
            (json!({ "mode": "INDICES", "byteStride": 3 }), "2 or 4"),
            (json!({ "mode": "LINES" }), "is not ATTRIBUTES"),
            (
                json!({ "filter": "OCTAHEDRAL", "byteStride": 12 }),
                "filter OCTAHEDRAL",
            ),
            (
                json!({ "count": 4_000_000_000u64, "byteStride": 256 }),
                "1 GiB",
            ),
        ] {
            let mut ext = ok.clone();
            for (k, v) in patch.as_object().expect("object") {
                ext[k] = v.clone();
            }
            let e = MeshoptView::parse(&ext)
                .and_then(|v| v.decode(&[0; 64]))
                .expect_err("refused");
            assert!(e.contains(wanted), "{ext}: {e}");
        }
        assert!(MeshoptView::parse(&json!({ "buffer": 0 })).is_err());
    }
}
