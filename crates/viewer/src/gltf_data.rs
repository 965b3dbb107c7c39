//! The bytes behind a glTF's accessors, read by precip rather than by the `gltf`
//! crate's reader (which asserts on the integer types `KHR_mesh_quantization` allows,
//! cannot load `EXT_meshopt_compression`'s fallback buffers and does not know
//! Draco): buffers, buffer views (plain, or meshopt-decoded), accessors of any
//! component type (normalized or not) as `f32`, indices, and Draco primitives.
//!
//! Every range is checked before it is read; a problem is a message naming the
//! accessor, view or buffer, which the loader turns into a `LoadError`.

use std::path::Path;

use gltf::accessor::{DataType, Dimensions};
use serde_json::Value;

use crate::meshopt_views::MeshoptView;

/// The buffers of a document; `EXT_meshopt_compression` fallback buffers are left
/// empty: they hold nothing a decoder needs (and often have no data at all).
pub fn load_buffers(
    document: &gltf::Document,
    base: &Path,
    mut blob: Option<Vec<u8>>,
) -> Result<Vec<gltf::buffer::Data>, String> {
    document
        .buffers()
        .map(|buffer| {
            let fallback = buffer
                .extension_value("EXT_meshopt_compression")
                .and_then(|e| e.get("fallback"))
                .and_then(Value::as_bool)
                == Some(true);
            if fallback {
                return Ok(gltf::buffer::Data(Vec::new()));
            }
            let data =
                gltf::buffer::Data::from_source_and_blob(buffer.source(), Some(base), &mut blob)
                    .map_err(|e| format!("buffer {}: {e}", buffer.index()))?;
            if data.len() < buffer.length() {
                return Err(format!(
                    "buffer {} holds {} bytes but says it has {}",
                    buffer.index(),
                    data.len(),
                    buffer.length()
                ));
            }
            Ok(data)
        })
        .collect()
}

/// The bytes of every buffer view: a range of its buffer, or decoded meshopt bytes.
#[derive(Debug)]
pub struct Views {
    bytes: Vec<Result<ViewBytes, String>>,
}

#[derive(Debug)]
enum ViewBytes {
    Range {
        buffer: usize,
        start: usize,
        end: usize,
    },
    Decoded(Vec<u8>),
}

impl Views {
    /// Resolves every view of `document` against `buffers` (meshopt views are decoded
    /// now; a broken view is an error only when an accessor reads it).
    #[must_use]
    pub fn new(document: &gltf::Document, buffers: &[gltf::buffer::Data]) -> Self {
        let bytes = document
            .views()
            .map(|view| {
                let i = view.index();
                if let Some(ext) = view.extension_value("EXT_meshopt_compression") {
                    let meshopt =
                        MeshoptView::parse(ext).map_err(|e| format!("buffer view {i}: {e}"))?;
                    let source = buffers
                        .get(meshopt.buffer)
                        .map(|b| &b.0[..])
                        .filter(|b| !b.is_empty())
                        .ok_or_else(|| {
                            format!(
                                "buffer view {i}: its compressed buffer {} is missing",
                                meshopt.buffer
                            )
                        })?;
                    return meshopt
                        .decode(source)
                        .map(ViewBytes::Decoded)
                        .map_err(|e| format!("buffer view {i} (EXT_meshopt_compression): {e}"));
                }
                let buffer = view.buffer().index();
                let data = buffers
                    .get(buffer)
                    .map(|b| &b.0[..])
                    .ok_or_else(|| format!("buffer view {i}: buffer {buffer} does not exist"))?;
                let (start, length) = (view.offset(), view.length());
                match start.checked_add(length) {
                    Some(end) if end <= data.len() => Ok(ViewBytes::Range { buffer, start, end }),
                    _ => Err(format!(
                        "buffer view {i} reaches past its buffer ({} bytes)",
                        data.len()
                    )),
                }
            })
            .collect();
        Self { bytes }
    }

    /// The bytes of view `index`.
    pub fn get<'a>(
        &'a self,
        index: usize,
        buffers: &'a [gltf::buffer::Data],
    ) -> Result<&'a [u8], String> {
        match self.bytes.get(index) {
            Some(Ok(ViewBytes::Decoded(bytes))) => Ok(bytes),
            Some(Ok(ViewBytes::Range { buffer, start, end })) => buffers
                .get(*buffer)
                .and_then(|b| b.0.get(*start..*end))
                .ok_or_else(|| format!("buffer view {index} is missing")),
            Some(Err(e)) => Err(e.clone()),
            None => Err(format!("buffer view {index} does not exist")),
        }
    }
}

/// Components per element of `dimensions`.
fn components(dimensions: Dimensions) -> usize {
    match dimensions {
        Dimensions::Scalar => 1,
        Dimensions::Vec2 => 2,
        Dimensions::Vec3 => 3,
        Dimensions::Vec4 | Dimensions::Mat2 => 4,
        Dimensions::Mat3 => 9,
        Dimensions::Mat4 => 16,
    }
}

/// Bytes of one component.
fn component_bytes(data_type: DataType) -> usize {
    match data_type {
        DataType::I8 | DataType::U8 => 1,
        DataType::I16 | DataType::U16 => 2,
        DataType::U32 | DataType::F32 => 4,
    }
}

/// One component at the start of `b` as `f32`: floats as they are, normalized
/// integers mapped to [0, 1] or [−1, 1] (glTF 2.0 §3.11), other integers as numbers.
fn component(b: &[u8], data_type: DataType, normalized: bool) -> f32 {
    match (data_type, normalized) {
        (DataType::F32, _) => f32::from_le_bytes([b[0], b[1], b[2], b[3]]),
        (DataType::I8, true) => (f32::from(b[0] as i8) / 127.0).max(-1.0),
        (DataType::I8, false) => f32::from(b[0] as i8),
        (DataType::U8, true) => f32::from(b[0]) / 255.0,
        (DataType::U8, false) => f32::from(b[0]),
        (DataType::I16, true) => (f32::from(i16::from_le_bytes([b[0], b[1]])) / 32767.0).max(-1.0),
        (DataType::I16, false) => f32::from(i16::from_le_bytes([b[0], b[1]])),
        (DataType::U16, true) => f32::from(u16::from_le_bytes([b[0], b[1]])) / 65535.0,
        (DataType::U16, false) => f32::from(u16::from_le_bytes([b[0], b[1]])),
        (DataType::U32, true) => {
            u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f32 / u32::MAX as f32
        }
        (DataType::U32, false) => u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f32,
    }
}

/// The elements of `accessor` (of `N` components, one of the `allowed` component
/// types), as `f32`, after checking every byte it reads lies in its view.
pub fn read_floats<const N: usize>(
    accessor: &gltf::Accessor<'_>,
    views: &Views,
    buffers: &[gltf::buffer::Data],
    allowed: &[DataType],
) -> Result<Vec<[f32; N]>, String> {
    let index = accessor.index();
    let data_type = accessor.data_type();
    if components(accessor.dimensions()) != N || !allowed.contains(&data_type) {
        return Err(format!(
            "accessor {index} is {:?} of {data_type:?}, which this attribute cannot be",
            accessor.dimensions()
        ));
    }
    let (bytes, stride) = element_bytes(accessor, views, buffers, N * component_bytes(data_type))?;
    let size = component_bytes(data_type);
    let normalized = accessor.normalized();
    Ok((0..accessor.count())
        .map(|i| {
            let at = accessor.offset() + i * stride;
            std::array::from_fn(|c| component(&bytes[at + c * size..], data_type, normalized))
        })
        .collect())
}

/// The indices of `accessor` (unsigned bytes, shorts or ints).
pub fn read_indices(
    accessor: &gltf::Accessor<'_>,
    views: &Views,
    buffers: &[gltf::buffer::Data],
) -> Result<Vec<u32>, String> {
    let index = accessor.index();
    let data_type = accessor.data_type();
    if accessor.dimensions() != Dimensions::Scalar
        || !matches!(data_type, DataType::U8 | DataType::U16 | DataType::U32)
    {
        return Err(format!(
            "accessor {index} ({:?} of {data_type:?}) cannot hold indices",
            accessor.dimensions()
        ));
    }
    let size = component_bytes(data_type);
    let (bytes, stride) = element_bytes(accessor, views, buffers, size)?;
    Ok((0..accessor.count())
        .map(|i| {
            let b = &bytes[accessor.offset() + i * stride..];
            match data_type {
                DataType::U8 => u32::from(b[0]),
                DataType::U16 => u32::from(u16::from_le_bytes([b[0], b[1]])),
                _ => u32::from_le_bytes([b[0], b[1], b[2], b[3]]),
            }
        })
        .collect())
}

/// The view bytes and stride of `accessor` with elements of `size` bytes, checked.
fn element_bytes<'a>(
    accessor: &gltf::Accessor<'_>,
    views: &'a Views,
    buffers: &'a [gltf::buffer::Data],
    size: usize,
) -> Result<(&'a [u8], usize), String> {
    let index = accessor.index();
    if accessor.sparse().is_some() {
        return Err(format!("accessor {index} is sparse (not supported)"));
    }
    let view = accessor
        .view()
        .ok_or_else(|| format!("accessor {index} has no buffer view"))?;
    let bytes = views.get(view.index(), buffers)?;
    let stride = view.stride().unwrap_or(size);
    if stride < size {
        return Err(format!(
            "buffer view {} has a stride below its element size",
            view.index()
        ));
    }
    let count = accessor.count();
    if count == 0 {
        return Err(format!("accessor {index} is empty"));
    }
    let end = (count - 1)
        .checked_mul(stride)
        .and_then(|x| x.checked_add(size))
        .and_then(|x| x.checked_add(accessor.offset()));
    if end.is_none_or(|end| end > bytes.len()) {
        return Err(format!(
            "accessor {index} ({count} elements) reaches past buffer view {} ({} bytes)",
            view.index(),
            bytes.len()
        ));
    }
    Ok((bytes, stride))
}

/// A primitive decoded from `KHR_draco_mesh_compression`: triangle indices and its
/// attributes by glTF semantic name (`POSITION`, `NORMAL`, `TEXCOORD_0`, `_SNOW_MASK`…).
#[derive(Debug, Default)]
pub struct DracoPrimitive {
    /// Triangle list.
    pub indices: Vec<u32>,
    /// Per point, `components` floats each.
    pub attributes: Vec<(String, usize, Vec<f32>)>,
}

impl DracoPrimitive {
    /// The values of attribute `semantic` as `N`-component elements.
    #[must_use]
    pub fn get<const N: usize>(&self, semantic: &str) -> Option<Result<Vec<[f32; N]>, String>> {
        let (_, n, values) = self.attributes.iter().find(|(s, _, _)| s == semantic)?;
        if *n != N {
            return Some(Err(format!(
                "Draco attribute {semantic} has {n} components, not {N}"
            )));
        }
        Some(Ok(values
            .chunks_exact(N)
            .map(|c| std::array::from_fn(|k| c[k]))
            .collect()))
    }
}

/// Decodes the Draco primitive the extension object `ext` describes, with the
/// pure-Rust `draco-core` decoder (Google's format re-implemented without C++, fuzzed,
/// with limits on what a stream may ask for). Its few internal `unwrap`s are behind a
/// `catch_unwind` so a hostile stream is an error, not a crash.
pub fn decode_draco(
    ext: &Value,
    views: &Views,
    buffers: &[gltf::buffer::Data],
) -> Result<DracoPrimitive, String> {
    let view = ext
        .get("bufferView")
        .and_then(Value::as_u64)
        .and_then(|v| usize::try_from(v).ok())
        .ok_or("KHR_draco_mesh_compression.bufferView is missing")?;
    let ids: Vec<(String, u32)> = ext
        .get("attributes")
        .and_then(Value::as_object)
        .ok_or("KHR_draco_mesh_compression.attributes is missing")?
        .iter()
        .map(|(name, id)| {
            id.as_u64()
                .and_then(|i| u32::try_from(i).ok())
                .map(|i| (name.clone(), i))
                .ok_or_else(|| format!("KHR_draco_mesh_compression attribute {name} is not an id"))
        })
        .collect::<Result<_, _>>()?;
    let bytes = views.get(view, buffers)?;
    let decoded = std::panic::catch_unwind(|| {
        let mut mesh = draco_core::Mesh::new();
        let mut buffer =
            draco_core::DecoderBuffer::new(bytes).with_limits(draco_core::DecodeLimits::default());
        draco_core::MeshDecoder::new()
            .decode(&mut buffer, &mut mesh)
            .map_err(|e| format!("Draco stream of buffer view {view}: {e:?}"))?;
        let points = mesh.num_points();
        let indices: Vec<u32> = mesh
            .faces()
            .iter()
            .flat_map(|f| f.iter().map(|p| p.0))
            .collect();
        let mut attributes = Vec::new();
        for (name, id) in &ids {
            let attribute = mesh
                .attribute_by_unique_id(*id)
                .ok_or_else(|| format!("Draco stream has no attribute {id} ({name})"))?;
            let n = attribute.num_components() as usize;
            attributes.push((name.clone(), n, attribute.read_f32s(points, n)));
        }
        Ok::<_, String>((
            points,
            DracoPrimitive {
                indices,
                attributes,
            },
        ))
    })
    .map_err(|_| {
        format!("the Draco stream of buffer view {view} is malformed (the decoder failed)")
    })??;
    let (points, primitive) = decoded;
    if let Some(&i) = primitive.indices.iter().find(|&&i| i as usize >= points) {
        return Err(format!("Draco index {i} is beyond its {points} points"));
    }
    Ok(primitive)
}
