// cull_particles.wgsl: view-cone culling and stable compaction of the particles into
// the lists the draws read (docs/model.md §5), in three kernels over 64-particle groups:
//   cull_count  — classifies each particle (drawn_kinds) and each group counts its
//                 drawn sprites, streaks and splats;
//   cull_scan   — one workgroup turns the counts into each group's offsets and writes
//                 the two indirect draws' instance counts and the splat count;
//   cull_write  — each drawn particle writes its index at its group's offset plus its
//                 rank within the group (reading its class, not classifying again).
// The lists keep buffer order, so a frame draws (and blends) in the same order with
// culling on or off: only what is outside the cone is missing. Sub-pixel particles
// are in neither list: the splat kernel draws them (`drawn_as`, particle_lists.wgsl).

// Read-only storage, as in render_scene.wgsl (why: there).
@group(0) @binding(0) var<storage, read> params: RenderParams;

// The frame's counts, for branches (particle_lists.wgsl).
fn frame_counts() -> vec4<u32> {
    return params.counts;
}
fn frame_pools() -> vec4<u32> {
    return params.pools;
}
@group(0) @binding(1) var<storage, read> particles: array<Particle>;
// (sprites, streaks, splats, 0) per group; the scan turns them into offsets.
@group(0) @binding(2) var<storage, read_write> group_counts: array<vec4<u32>>;
@group(0) @binding(3) var<storage, read_write> drawn: array<u32>;
@group(0) @binding(4) var<storage, read_write> draws: FrameDraws;
// How each particle is drawn this frame: its class (DRAWN_*) in bits 0–7 and its rank
// among its workgroup's particles of that class from bit 8, written by cull_count so
// cull_write reads one word per particle and places it with no barrier.
@group(0) @binding(5) var<storage, read_write> drawn_kinds: array<u32>;
// The frame's snow quads, for their capacity: the snow draw takes the instances
// whose quads are kept, a second draw the rest (render_particles.wgsl).
@group(0) @binding(6) var<storage, read> cull_snow_quads: array<SnowQuad>;

const RANK_SHIFT: u32 = 8u;
const CLASS_MASK: u32 = 255u;

var<workgroup> group_kinds: array<u32, 64>;
var<workgroup> partial: array<vec4<u32>, 64>;

@compute @workgroup_size(64)
fn cull_count(@builtin(local_invocation_index) lid: u32, @builtin(workgroup_id) wid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let g = wid.x + wid.y * groups.x;
    let i = g * 64u + lid;
    group_kinds[lid] = drawn_as(i);
    workgroupBarrier();
    if (lid == 0u) {
        // The first lane counts the group's classes in order: each particle's rank
        // among its class is the count before it.
        var c = vec4<u32>(0u);
        for (var k = 0u; k < 64u; k++) {
            let kind = group_kinds[k];
            let rank = select(select(select(0u, c.z, kind == DRAWN_SPLAT), c.y, kind == DRAWN_RAIN), c.x, kind == DRAWN_SNOW);
            let j = g * 64u + k;
            if (j < params.counts.x) {
                drawn_kinds[j] = kind | (rank << RANK_SHIFT);
            }
            c += vec4<u32>(u32(kind == DRAWN_SNOW), u32(kind == DRAWN_RAIN), u32(kind == DRAWN_SPLAT), 0u);
        }
        group_counts[g] = c;
    }
}

@compute @workgroup_size(64)
fn cull_scan(@builtin(local_invocation_index) lid: u32) {
    let groups = params.counts.z;
    let per = (groups + 63u) / 64u;
    let start = min(lid * per, groups);
    let end = min(start + per, groups);
    var sum = vec4<u32>(0u);
    for (var k = start; k < end; k++) {
        sum += group_counts[k];
    }
    partial[lid] = sum;
    workgroupBarrier();
    if (lid == 0u) {
        var total = vec4<u32>(0u);
        for (var k = 0u; k < 64u; k++) {
            let s = partial[k];
            partial[k] = total;
            total += s;
        }
        // Each sprite drawn as its copies (snow_copies in particle_lists.wgsl): those
        // whose quads are kept, then the rest.
        let sprites = total.x * snow_copies();
        let kept = min(sprites, arrayLength(&cull_snow_quads));
        draws = FrameDraws(
            DrawArgs(SNOW_SPRITE_VERTICES, kept, 0u, 0u),
            DrawArgs(RAIN_TETRAHEDRON_VERTICES, total.y, 0u, 0u),
            total.z, total.x, 0u, 0u,
            DrawArgs(SNOW_SPRITE_VERTICES, sprites - kept, 0u, 0u),
        );
    }
    workgroupBarrier();
    var run = partial[lid];
    for (var k = start; k < end; k++) {
        let c = group_counts[k];
        group_counts[k] = run;
        run += c;
    }
}

@compute @workgroup_size(64)
fn cull_write(@builtin(local_invocation_index) lid: u32, @builtin(workgroup_id) wid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let g = wid.x + wid.y * groups.x;
    let i = g * 64u + lid;
    let n = params.counts.x;
    if (i >= n) {
        return;
    }
    let word = drawn_kinds[i];
    let kind = word & CLASS_MASK;
    let rank = word >> RANK_SHIFT;
    let offset = group_counts[g];
    if (kind == DRAWN_SNOW) {
        drawn[offset.x + rank] = i;
    } else if (kind == DRAWN_RAIN) {
        drawn[n + offset.y + rank] = i;
    } else if (kind == DRAWN_SPLAT) {
        drawn[2u * n + offset.z + rank] = i;
    }
}
