//! glTF 2.0 → [`Scene`]: any valid file (.gltf with external .bin or data URIs, .glb),
//! indexed or not, the node hierarchy with its transforms, base colour factor and
//! texture, snow eligibility by docs/architecture.md §6 (`_SNOW_MASK`, then `extras.snow` on the
//! material, mesh or node (nearest ancestor first), then the slope).
//!
//! Quantized and compressed geometry loads as real pipelines write it:
//! `KHR_mesh_quantization` (integer and normalized attributes), `EXT_meshopt_compression`
//! (meshoptimizer, through the `meshopt` crate) and `KHR_draco_mesh_compression` (the
//! pure-Rust `draco-core` decoder), with `KHR_texture_transform` applied to the UVs; the
//! bytes are read by [`crate::gltf_data`]. A file that *requires* any other extension is
//! refused with an error naming it.
//!
//! Content the viewer does not draw (points, lines, cameras, skins, animation,
//! unknown extensions, float textures) is skipped and listed in the
//! [`LoadReport`]; what cannot be shown (no triangles at all, broken buffers,
//! accessors out of range, indices beyond the vertices, non-finite positions) is a
//! [`LoadError`] naming the file and the part. Every accessor is checked against its
//! buffer before it is read, so no input reaches the `gltf` crate's debug assertions;
//! a panic inside that crate (a bug there) is still caught and reported as an error.

use std::path::{Path, PathBuf};

use glam::{Mat3, Mat4, Vec2, Vec3};
use gltf::accessor::DataType;
use gltf::mesh::Mode;
use precip_model::{Material, Mesh, PreparedScene, Scene, SceneReport, TextureRgba8};

use crate::eligibility::{SurfaceTag, snow_extra, surface_extra};
use crate::error::LoadError;
use crate::gltf_data::{
    DracoPrimitive, Views, decode_draco, load_buffers, read_floats, read_indices,
};
use crate::node_graph::{find_cycle, walk_order};

/// What loading skipped or changed.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct LoadReport {
    /// One line per thing skipped, saying why.
    pub skipped: Vec<String>,
    /// Primitives read.
    pub primitives: usize,
    /// Primitives whose eligibility came from `_SNOW_MASK`.
    pub snow_mask_attribute: usize,
    /// Primitives whose eligibility came from `extras.snow`.
    pub snow_extras: usize,
    /// Where each primitive's snow eligibility and surface came from, by the
    /// primitive's name (`precip inspect` prints them).
    pub tags: Vec<PrimitiveTags>,
    /// What `Scene::prepare` did (degenerate triangles, computed normals, slope).
    pub scene: SceneReport,
}

/// Where a primitive's tag came from.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum TagSource {
    /// The `_SNOW_MASK` vertex attribute (eligibility only).
    Attribute,
    /// `extras` on what the string names: `material 2 "Asphalt"`, `mesh "road"`,
    /// `node 4 "terrain"` (the nearest of material, mesh, node up the hierarchy).
    Extras(String),
    /// No tag: eligibility from the slope, the surface by the default (paved
    /// where no snow lies, else soil).
    Untagged,
}

impl std::fmt::Display for TagSource {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Attribute => f.write_str("the _SNOW_MASK attribute"),
            Self::Extras(on) => write!(f, "extras on {on}"),
            Self::Untagged => f.write_str("no tag"),
        }
    }
}

/// Where one primitive's tags came from.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PrimitiveTags {
    /// The primitive, as its mesh is named (`road primitive 0`).
    pub primitive: String,
    /// Its snow eligibility's.
    pub eligibility: TagSource,
    /// Its surface's.
    pub surface: TagSource,
}

/// A loaded, prepared scene.
#[derive(Debug, Clone)]
pub struct LoadedScene {
    /// The scene, prepared.
    pub scene: PreparedScene,
    /// What was skipped.
    pub report: LoadReport,
}

/// Loads the glTF or GLB file at `path` (external buffers and images relative to it).
pub fn load_scene(path: &Path) -> Result<LoadedScene, LoadError> {
    let file = path.to_path_buf();
    guarded(&file, || {
        let bytes = std::fs::read(path).map_err(|e| LoadError::Gltf {
            file: file.clone(),
            detail: e.to_string(),
        })?;
        let base = path.parent().unwrap_or(Path::new("."));
        import(&file, &bytes, base)
    })
}

/// Loads a glTF or GLB from bytes (`name` names it in messages). Buffers and images
/// must be inside it (GLB chunk or data URIs): a slice has no directory, so external
/// references fail with an error naming them.
pub fn load_scene_from_slice(bytes: &[u8], name: &str) -> Result<LoadedScene, LoadError> {
    let file = PathBuf::from(name);
    guarded(&file, || {
        import(&file, bytes, Path::new("/nonexistent/precip-slice"))
    })
}

/// Reads the document and its buffers (errors are fatal) and its images (a broken
/// image is skipped with a warning: the mesh is drawn untextured).
fn import(file: &Path, bytes: &[u8], base: &Path) -> Result<LoadedScene, LoadError> {
    let gltf_error = |e: gltf::Error| LoadError::Gltf {
        file: file.to_path_buf(),
        detail: e.to_string(),
    };
    let gltf = gltf::Gltf::from_slice_without_validation(bytes).map_err(gltf_error)?;
    let blob = gltf.blob;
    let json = gltf.document.into_json();
    // gltf-json 1.4's validation indexes each primitive's POSITION accessor before
    // checking that it exists (a panic on a bad index): check every attribute first.
    for (m, mesh) in json.meshes.iter().enumerate() {
        for (p, primitive) in mesh.primitives.iter().enumerate() {
            for (semantic, index) in &primitive.attributes {
                if index.value() >= json.accessors.len() {
                    return Err(LoadError::Invalid {
                        file: file.to_path_buf(),
                        problem: format!(
                            "mesh {m} primitive {p}: attribute {semantic:?} names accessor {} but the file has {}",
                            index.value(),
                            json.accessors.len()
                        ),
                    });
                }
            }
        }
    }
    // gltf 1.4's `Image::source` unwraps a missing `uri` (an image that is `{}`) and a
    // missing `mimeType` beside a `bufferView`: such images are found here, in the
    // JSON, and never handed to it.
    let image_problems: Vec<Option<&'static str>> = json
        .images
        .iter()
        .map(
            |image| match (&image.buffer_view, &image.uri, &image.mime_type) {
                (None, None, _) => Some("has neither a uri nor a bufferView"),
                (Some(_), _, None) => Some("has a bufferView but no mimeType"),
                _ => None,
            },
        )
        .collect();
    check_required_extensions(&json).map_err(|problem| LoadError::Invalid {
        file: file.to_path_buf(),
        problem,
    })?;
    validate(&json).map_err(|detail| LoadError::Gltf {
        file: file.to_path_buf(),
        detail,
    })?;
    let document = gltf::Document::from_json_without_validation(json);
    let buffers = load_buffers(&document, base, blob).map_err(|detail| LoadError::Gltf {
        file: file.to_path_buf(),
        detail,
    })?;
    let mut warnings = Vec::new();
    let images = import_images(&document, base, &buffers, &image_problems, &mut warnings);
    let mut loaded = convert(file, &document, &buffers, &images)?;
    loaded.report.skipped.extend(warnings);
    Ok(loaded)
}

/// Extensions a file may require: the compressions and quantization precip decodes,
/// the texture transform it applies, and those the `gltf` crate reads itself.
pub const SUPPORTED_REQUIRED_EXTENSIONS: &[&str] = &[
    "KHR_mesh_quantization",
    "KHR_draco_mesh_compression",
    "EXT_meshopt_compression",
    "KHR_texture_transform",
    "KHR_materials_unlit",
];

/// A file that requires an extension precip cannot honour is refused, naming it.
fn check_required_extensions(json: &gltf::json::Root) -> Result<(), String> {
    let missing: Vec<&str> = json
        .extensions_required
        .iter()
        .map(String::as_str)
        .filter(|e| !SUPPORTED_REQUIRED_EXTENSIONS.contains(e))
        .collect();
    if missing.is_empty() {
        return Ok(());
    }
    Err(format!(
        "the file requires {} {}, which precip does not support (it reads {}); export it without {}",
        if missing.len() == 1 {
            "extension"
        } else {
            "extensions"
        },
        missing.join(", "),
        SUPPORTED_REQUIRED_EXTENSIONS.join(", "),
        if missing.len() == 1 { "it" } else { "them" },
    ))
}

/// gltf-json's validation (every index in range, required fields present), less what
/// the extensions precip decodes make valid: accessors whose data is in a Draco
/// stream have no `bufferView`, and the required extensions were checked above.
fn validate(json: &gltf::json::Root) -> Result<(), String> {
    use gltf::json::validation::{Error, Validate};
    let draco_accessors: std::collections::HashSet<String> = json
        .meshes
        .iter()
        .flat_map(|m| &m.primitives)
        .filter(|p| {
            p.extensions
                .as_ref()
                .is_some_and(|e| e.others.contains_key("KHR_draco_mesh_compression"))
        })
        .flat_map(|p| {
            p.attributes
                .values()
                .map(|a| a.value())
                .chain(p.indices.map(|i| i.value()))
        })
        .map(|a| format!("accessors[{a}].bufferView"))
        .collect();
    let mut problems = Vec::new();
    json.validate(json, gltf::json::Path::new, &mut |path, error| {
        let path = path().to_string();
        let decoded_elsewhere = match error {
            Error::Unsupported => path.starts_with("extensionsRequired"),
            Error::Missing => draco_accessors.contains(&path),
            _ => false,
        };
        if !decoded_elsewhere {
            problems.push(format!("{path}: {error}"));
        }
    });
    if problems.is_empty() {
        return Ok(());
    }
    let more = problems.len().saturating_sub(4);
    problems.truncate(4);
    Err(format!(
        "invalid glTF: {}{}",
        problems.join("; "),
        if more > 0 {
            format!(" (and {more} more)")
        } else {
            String::new()
        }
    ))
}

/// Each image decoded on its own (a broken one is `None`, with a warning, and its
/// meshes are drawn untextured), after the checks the glTF reader would otherwise
/// make with a panic: `problems` from the JSON, and buffer views inside their buffers.
fn import_images(
    document: &gltf::Document,
    base: &Path,
    buffers: &[gltf::buffer::Data],
    problems: &[Option<&'static str>],
    warnings: &mut Vec<String>,
) -> Vec<Option<gltf::image::Data>> {
    document
        .images()
        .map(|image| {
            let i = image.index();
            if let Some(problem) = problems.get(i).copied().flatten() {
                warnings.push(format!("image {i} {problem}; drawn untextured"));
                return None;
            }
            let source = image.source();
            if let gltf::image::Source::View { view, .. } = &source {
                let inside = buffers.get(view.buffer().index()).is_some_and(|b| {
                    view.offset()
                        .checked_add(view.length())
                        .is_some_and(|end| end <= b.len())
                });
                if !inside {
                    warnings.push(format!(
                        "image {i}: its buffer view reaches past its buffer; drawn untextured"
                    ));
                    return None;
                }
            }
            match gltf::image::Data::from_source(source, Some(base), buffers) {
                Ok(data) => Some(data),
                Err(e) => {
                    warnings.push(format!("image {i}: {e}; drawn untextured"));
                    None
                }
            }
        })
        .collect()
}

/// Runs `f`, turning a panic inside the glTF reader into an error.
fn guarded(
    file: &Path,
    f: impl FnOnce() -> Result<LoadedScene, LoadError>,
) -> Result<LoadedScene, LoadError> {
    std::panic::catch_unwind(std::panic::AssertUnwindSafe(f)).unwrap_or_else(|_| {
        Err(LoadError::Gltf {
            file: file.to_path_buf(),
            detail: "the glTF reader failed on this file (it is malformed)".into(),
        })
    })
}

/// Component types of each attribute: float, or the integer types
/// `KHR_mesh_quantization` allows (normalized or not; glTF 2.0 §3.7.2.1 and the
/// extension's table).
const POSITION_TYPES: &[DataType] = &[
    DataType::F32,
    DataType::I8,
    DataType::U8,
    DataType::I16,
    DataType::U16,
];
const NORMAL_TYPES: &[DataType] = &[DataType::F32, DataType::I8, DataType::I16];
const UV_TYPES: &[DataType] = &[
    DataType::F32,
    DataType::I8,
    DataType::U8,
    DataType::I16,
    DataType::U16,
];
const MASK_TYPES: &[DataType] = &[DataType::F32, DataType::U8, DataType::U16];

/// `uv` through `KHR_texture_transform`: offset · rotation · scale (the extension's
/// matrix, rotation counter-clockwise in UV space).
#[must_use]
pub fn texture_transformed(uv: Vec2, offset: [f32; 2], rotation_rad: f32, scale: [f32; 2]) -> Vec2 {
    let (sin, cos) = rotation_rad.sin_cos();
    let s = uv * Vec2::from(scale);
    Vec2::new(
        offset[0] + cos * s.x + sin * s.y,
        offset[1] - sin * s.x + cos * s.y,
    )
}

/// RGBA8 from a decoded glTF image, or `None` for formats the viewer does not show.
fn rgba8(image: &gltf::image::Data) -> Option<TextureRgba8> {
    use gltf::image::Format;
    let (w, h) = (image.width, image.height);
    let n = (w as usize).checked_mul(h as usize)?;
    let px = &image.pixels;
    let channels = match image.format {
        Format::R8 => 1,
        Format::R8G8 => 2,
        Format::R8G8B8 => 3,
        Format::R8G8B8A8 => 4,
        Format::R16 => 2,
        Format::R16G16 => 4,
        Format::R16G16B16 => 6,
        Format::R16G16B16A16 => 8,
        _ => return None,
    };
    if px.len() < n * channels {
        return None;
    }
    let wide = matches!(
        image.format,
        Format::R16 | Format::R16G16 | Format::R16G16B16 | Format::R16G16B16A16
    );
    let (bytes_per, count) = if wide {
        (2, channels / 2)
    } else {
        (1, channels)
    };
    let mut out = Vec::with_capacity(n * 4);
    for i in 0..n {
        // The high byte of 16-bit channels (little endian).
        let c = |k: usize| px[i * channels + k * bytes_per + bytes_per - 1];
        let (r, g, b, a) = match count {
            1 => (c(0), c(0), c(0), 255),
            2 => (c(0), c(0), c(0), c(1)),
            3 => (c(0), c(1), c(2), 255),
            _ => (c(0), c(1), c(2), c(3)),
        };
        out.extend_from_slice(&[r, g, b, a]);
    }
    Some(TextureRgba8 {
        width_px: w,
        height_px: h,
        rgba8: out,
    })
}

struct Converter<'a> {
    file: &'a Path,
    buffers: &'a [gltf::buffer::Data],
    views: &'a Views,
    images: &'a [Option<gltf::image::Data>],
    report: LoadReport,
    meshes: Vec<Mesh>,
}

/// What a node passes to its meshes and children: the nearest `extras` up the
/// hierarchy, each with what it was on.
#[derive(Debug, Clone, Default)]
struct Inherited {
    snow: Option<(f32, String)>,
    surface: Option<(SurfaceTag, String)>,
}

/// `kind index "name"` (or `kind index` without a name) naming where a tag was.
fn labelled(kind: &str, index: usize, name: Option<&str>) -> String {
    name.map_or_else(
        || format!("{kind} {index}"),
        |n| format!("{kind} {index} \"{n}\""),
    )
}

impl Converter<'_> {
    fn invalid(&self, problem: String) -> LoadError {
        LoadError::Invalid {
            file: self.file.to_path_buf(),
            problem,
        }
    }

    /// The meshes under the scene's `roots`, walked with an explicit stack (see
    /// [`crate::node_graph`]): each node once, its transform and snow value from its
    /// parent's.
    fn nodes(&mut self, document: &gltf::Document, roots: &[usize]) -> Result<(), LoadError> {
        let nodes: Vec<gltf::Node<'_>> = document.nodes().collect();
        let children: Vec<Vec<usize>> = nodes
            .iter()
            .map(|n| n.children().map(|c| c.index()).collect())
            .collect();
        if let Some(cycle) = find_cycle(&children) {
            let path: Vec<String> = cycle.iter().map(usize::to_string).collect();
            return Err(self.invalid(format!(
                "nodes {} form a cycle (a node is its own ancestor); glTF requires the node hierarchy to be trees",
                path.join(" → ")
            )));
        }
        let (order, again) = walk_order(&children, roots);
        for node in again {
            self.report.skipped.push(format!(
                "node {node}: reached a second time (two parents, or a root listed twice); drawn once"
            ));
        }
        let mut placed: Vec<(Mat4, Inherited)> = Vec::with_capacity(order.len());
        for visit in order {
            let (parent, inherited) = visit
                .parent
                .and_then(|p| placed.get(p).cloned())
                .unwrap_or((Mat4::IDENTITY, Inherited::default()));
            let placement = self.node(&nodes[visit.node], parent, inherited)?;
            placed.push(placement);
        }
        Ok(())
    }

    /// One node's meshes; returns its world transform and snow value for its children.
    fn node(
        &mut self,
        node: &gltf::Node<'_>,
        parent: Mat4,
        inherited: Inherited,
    ) -> Result<(Mat4, Inherited), LoadError> {
        let local = Mat4::from_cols_array_2d(&node.transform().matrix());
        let world = parent * local;
        let bad = |e: String| self.invalid(format!("node {}: {e}", node.index()));
        let on = labelled("node", node.index(), node.name());
        let here = Inherited {
            snow: snow_extra(node.extras())
                .map_err(bad)?
                .map(|s| (s, on.clone()))
                .or(inherited.snow),
            surface: surface_extra(node.extras())
                .map_err(bad)?
                .map(|s| (s, on))
                .or(inherited.surface),
        };
        if let Some(mesh) = node.mesh() {
            if world.is_finite() {
                self.mesh(&mesh, world, here.clone())?;
            } else {
                self.report
                    .skipped
                    .push(format!("node {}: a non-finite transform", node.index()));
            }
        }
        if node.camera().is_some() || node.skin().is_some() {
            self.report.skipped.push(format!(
                "node {}: cameras and skins are not used",
                node.index()
            ));
        }
        Ok((world, here))
    }

    fn mesh(
        &mut self,
        mesh: &gltf::Mesh<'_>,
        world: Mat4,
        node: Inherited,
    ) -> Result<(), LoadError> {
        let mesh_name = mesh
            .name()
            .map_or_else(|| format!("mesh {}", mesh.index()), str::to_owned);
        let bad = |e: String| self.invalid(format!("{mesh_name}: {e}"));
        let on = labelled("mesh", mesh.index(), mesh.name());
        let outer = Inherited {
            snow: snow_extra(mesh.extras())
                .map_err(bad)?
                .map(|s| (s, on.clone()))
                .or(node.snow),
            surface: surface_extra(mesh.extras())
                .map_err(bad)?
                .map(|s| (s, on))
                .or(node.surface),
        };
        for primitive in mesh.primitives() {
            let name = format!("{mesh_name} primitive {}", primitive.index());
            match self.primitive(&primitive, &name, world, outer.clone()) {
                Ok(Some(m)) => {
                    self.report.primitives += 1;
                    self.meshes.push(m);
                }
                Ok(None) => {}
                Err(problem) => return Err(self.invalid(format!("{name}: {problem}"))),
            }
        }
        Ok(())
    }

    fn primitive(
        &mut self,
        primitive: &gltf::Primitive<'_>,
        name: &str,
        world: Mat4,
        outer: Inherited,
    ) -> Result<Option<Mesh>, String> {
        let mode = primitive.mode();
        if !matches!(
            mode,
            Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan
        ) {
            self.report
                .skipped
                .push(format!("{name}: {mode:?} are not drawn"));
            return Ok(None);
        }
        let (views, buffers) = (self.views, self.buffers);
        let draco = primitive
            .extension_value("KHR_draco_mesh_compression")
            .map(|ext| decode_draco(ext, views, buffers))
            .transpose()?;
        // An attribute from the Draco stream when it carries it, else its accessor.
        let attribute = |semantic: &gltf::Semantic| primitive.get(semantic);
        fn read<const N: usize>(
            draco: Option<&DracoPrimitive>,
            key: &str,
            accessor: Option<gltf::Accessor<'_>>,
            views: &Views,
            buffers: &[gltf::buffer::Data],
            allowed: &[DataType],
        ) -> Result<Option<Vec<[f32; N]>>, String> {
            if let Some(values) = draco.and_then(|d| d.get::<N>(key)) {
                return values.map(Some);
            }
            accessor
                .map(|a| read_floats::<N>(&a, views, buffers, allowed))
                .transpose()
        }
        let Some(position) = attribute(&gltf::Semantic::Positions) else {
            self.report
                .skipped
                .push(format!("{name}: no POSITION attribute"));
            return Ok(None);
        };
        let positions: Vec<Vec3> = read::<3>(
            draco.as_ref(),
            "POSITION",
            Some(position),
            views,
            buffers,
            POSITION_TYPES,
        )?
        .unwrap_or_default()
        .into_iter()
        .map(Vec3::from)
        .collect();
        let n = positions.len();
        if let Some(v) = positions.iter().position(|p| !p.is_finite()) {
            return Err(format!("vertex {v} has a non-finite position"));
        }
        let normals: Vec<Vec3> = read::<3>(
            draco.as_ref(),
            "NORMAL",
            attribute(&gltf::Semantic::Normals),
            views,
            buffers,
            NORMAL_TYPES,
        )?
        .unwrap_or_default()
        .into_iter()
        .map(Vec3::from)
        .collect();
        if !normals.is_empty() && normals.len() != n {
            return Err(format!("{} normals for {n} positions", normals.len()));
        }
        let material = primitive.material();
        let pbr = material.pbr_metallic_roughness();
        let mut texture = None;
        let mut uvs = Vec::new();
        if let Some(info) = pbr.base_color_texture() {
            let transform = info.texture_transform();
            let set = transform
                .as_ref()
                .and_then(|t| t.tex_coord())
                .unwrap_or(info.tex_coord());
            let source = info.texture().source().index();
            let key = format!("TEXCOORD_{set}");
            let coords = read::<2>(
                draco.as_ref(),
                &key,
                attribute(&gltf::Semantic::TexCoords(set)),
                views,
                buffers,
                UV_TYPES,
            )?;
            match (coords, self.images.get(source).and_then(Option::as_ref)) {
                (Some(coords), Some(image)) if coords.len() == n => {
                    uvs = coords.into_iter().map(Vec2::from).collect();
                    if let Some(t) = transform {
                        let (offset, rotation, scale) = (t.offset(), t.rotation(), t.scale());
                        for uv in &mut uvs {
                            *uv = texture_transformed(*uv, offset, rotation, scale);
                        }
                    }
                    texture = rgba8(image);
                    if texture.is_none() {
                        self.report.skipped.push(format!(
                            "{name}: image {source}'s pixel format is not shown"
                        ));
                    }
                }
                _ => self.report.skipped.push(format!(
                    "{name}: base-colour texture without TEXCOORD_{set} or image: drawn untextured"
                )),
            }
        }
        let mut snow_eligibility = Vec::new();
        let mut eligibility_from = TagSource::Untagged;
        let material_on = material.index().map_or_else(
            || "the default material".to_owned(),
            |i| labelled("material", i, material.name()),
        );
        let mask = attribute(&gltf::Semantic::Extras("SNOW_MASK".into()));
        if let Some(values) = read::<1>(
            draco.as_ref(),
            "_SNOW_MASK",
            mask,
            views,
            buffers,
            MASK_TYPES,
        )? {
            if values.len() != n {
                return Err(format!(
                    "_SNOW_MASK has {} values for {n} vertices",
                    values.len()
                ));
            }
            snow_eligibility = values
                .into_iter()
                .map(|[x]| {
                    if x.is_finite() {
                        x.clamp(0.0, 1.0)
                    } else {
                        0.0
                    }
                })
                .collect();
            self.report.snow_mask_attribute += 1;
            eligibility_from = TagSource::Attribute;
        } else {
            let material_snow = snow_extra(material.extras())?.map(|s| (s, material_on.clone()));
            if let Some((e, on)) = material_snow.or(outer.snow) {
                snow_eligibility = vec![e; n];
                self.report.snow_extras += 1;
                eligibility_from = TagSource::Extras(on);
            }
        }
        let mut indices: Vec<u32> = match (&draco, primitive.indices()) {
            (Some(d), _) => d.indices.clone(),
            (None, Some(a)) => read_indices(&a, views, buffers)?,
            (None, None) => (0..n as u32).collect(),
        };
        if let Some(&i) = indices.iter().find(|&&i| i as usize >= n) {
            return Err(format!("index {i} is beyond its {n} vertices"));
        }
        indices = match mode {
            Mode::TriangleStrip => (2..indices.len())
                .flat_map(|k| {
                    let (a, b, c) = (indices[k - 2], indices[k - 1], indices[k]);
                    if k % 2 == 0 { [a, b, c] } else { [b, a, c] }
                })
                .collect(),
            Mode::TriangleFan => (2..indices.len())
                .flat_map(|k| [indices[0], indices[k - 1], indices[k]])
                .collect(),
            _ => {
                let whole = indices.len() / 3 * 3;
                indices.truncate(whole);
                indices
            }
        };
        // World space: positions by the node's matrix, normals by its inverse transpose;
        // a mirroring transform flips the winding.
        let normal_matrix = Mat3::from_mat4(world).inverse().transpose();
        let positions_m: Vec<Vec3> = positions
            .iter()
            .map(|&p| world.transform_point3(p))
            .collect();
        let normals: Vec<Vec3> = normals
            .iter()
            .map(|&v| (normal_matrix * v).normalize_or(Vec3::Y))
            .collect();
        if Mat3::from_mat4(world).determinant() < 0.0 {
            for t in indices.chunks_exact_mut(3) {
                t.swap(1, 2);
            }
        }
        let f = pbr.base_color_factor();
        let tag = surface_extra(material.extras())?
            .map(|s| (s, material_on))
            .or(outer.surface);
        self.report.tags.push(PrimitiveTags {
            primitive: name.to_owned(),
            eligibility: eligibility_from,
            surface: tag
                .as_ref()
                .map_or(TagSource::Untagged, |(_, on)| TagSource::Extras(on.clone())),
        });
        let tag = tag.map(|(t, _)| t);
        Ok(Some(Mesh {
            name: name.to_owned(),
            positions_m,
            normals,
            uvs: if texture.is_some() { uvs } else { Vec::new() },
            indices,
            snow_eligibility,
            surface: tag.map(|t| t.surface),
            sea: tag.is_some_and(|t| t.sea),
            material: Material {
                base_colour: f,
                base_colour_texture: texture,
            },
        }))
    }
}

fn convert(
    file: &Path,
    document: &gltf::Document,
    buffers: &[gltf::buffer::Data],
    images: &[Option<gltf::image::Data>],
) -> Result<LoadedScene, LoadError> {
    let views = Views::new(document, buffers);
    let mut c = Converter {
        file,
        buffers,
        views: &views,
        images,
        report: LoadReport::default(),
        meshes: Vec::new(),
    };
    for ext in document.extensions_used() {
        if !SUPPORTED_REQUIRED_EXTENSIONS.contains(&ext) {
            c.report
                .skipped
                .push(format!("extension {ext} is not used"));
        }
    }
    if document.animations().next().is_some() {
        c.report.skipped.push("animations are not played".into());
    }
    let scene = document
        .default_scene()
        .or_else(|| document.scenes().next());
    match scene {
        Some(scene) => {
            let roots: Vec<usize> = scene.nodes().map(|n| n.index()).collect();
            c.nodes(document, &roots)?;
        }
        None => {
            // No scene: every mesh once, untransformed.
            for mesh in document.meshes() {
                c.mesh(&mesh, Mat4::IDENTITY, Inherited::default())?;
            }
        }
    }
    let Converter {
        mut report, meshes, ..
    } = c;
    if meshes.is_empty() {
        let detail = if report.skipped.is_empty() {
            "the file has no meshes".to_owned()
        } else {
            report.skipped.join("; ")
        };
        return Err(LoadError::NoTriangles {
            file: file.to_path_buf(),
            detail,
        });
    }
    let (scene, scene_report) = Scene { meshes }.prepare().map_err(|source| match source {
        precip_model::SceneError::Empty => LoadError::NoTriangles {
            file: file.to_path_buf(),
            detail: "every triangle is degenerate".into(),
        },
        source => LoadError::Scene {
            file: file.to_path_buf(),
            source,
        },
    })?;
    report.scene = scene_report;
    Ok(LoadedScene { scene, report })
}
