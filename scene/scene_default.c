/* scene_default.c - pg_scene_create_default: a generated, deterministic atrium (no files).
 *
 * Layout (metres, Y up, floor at y = 0, centred on the origin; ~30 x 12 x 15 like Sponza):
 *   - a closed box room x in [-15, 15], z in [-7.5, 7.5], y in [0, 12]: tiled floor, brick walls,
 *     plain ceiling; every surface faces the inside;
 *   - two arcades along X at z = +-4: 9 marble columns each (x = -12 .. 12 step 3) with stone
 *     plinths and abaci, round arches (extruded half-annuli: spandrel faces with a semicircular
 *     opening plus the intrados) carrying a stone wall;
 *   - an upper gallery over each aisle (a slab at y = 5.75 .. 6 with a tiled floor), a second,
 *     smaller arcade on it reaching the ceiling, alpha-masked bronze grilles as its balustrade;
 *   - red drapes hanging from the gallery edge in alternate bays.
 * Materials (7): floor tiles (+ normal map), brick (+ normal map), stone, marble, plain ceiling,
 * grille (alpha MASK, cutoff 0.5, double-sided), plain red drape (double-sided). Textures are
 * generated RGBA8 (power-of-two, tileable) with full mip chains; UVs are world metres divided by
 * each texture's repeat size. One primitive per material. Triangle winding is CCW seen from the
 * side the normal points to; tangents are computed from the UVs (pg_mesh_compute_tangents).
 * Everything uses integer hashing and fixed float math: two calls give identical bytes.
 */
#include "scene.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define PI_F 3.14159265358979323846f

enum {
    MAT_FLOOR,
    MAT_BRICK,
    MAT_STONE,
    MAT_MARBLE,
    MAT_CEILING,
    MAT_GRILLE,
    MAT_DRAPE,
    MAT_COUNT
};

/* ---- room dimensions ---- */
#define HX 15.0f       /* half length (x) */
#define HZ 7.5f        /* half width (z) */
#define ROOM_H 12.0f
#define ROW_Z 4.0f     /* arcade rows at z = +-ROW_Z */
#define WALL_T 0.6f    /* arcade wall thickness */
#define BAY 3.0f       /* column spacing */
#define N_COLS 9
#define COL_X0 (-12.0f)
#define SLAB_Y0 5.75f
#define SLAB_Y1 6.0f
#define UPPER_SCALE 0.6f

/* texture repeat sizes in metres */
#define TS_FLOOR 2.0f
#define TS_BRICK 2.0f
#define TS_STONE 2.0f
#define TS_MARBLE 1.0f
#define TS_GRILLE 0.5f

/* ------------------------------------------------------------------------------------------ */
/* mesh building                                                                               */

typedef struct mesh_b {
    pg_vertex *v;
    uint32_t nv, cv;
    uint32_t *idx;
    uint32_t ni, ci;
    bool oom;
} mesh_b;

typedef struct v3 {
    float x, y, z;
} v3;

static v3 mk(float x, float y, float z)
{
    v3 r = {x, y, z};
    return r;
}
static v3 add(v3 a, v3 b) { return mk(a.x + b.x, a.y + b.y, a.z + b.z); }
static v3 sub(v3 a, v3 b) { return mk(a.x - b.x, a.y - b.y, a.z - b.z); }
static v3 scl(v3 a, float s) { return mk(a.x * s, a.y * s, a.z * s); }
static float dot(v3 a, v3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static v3 cross(v3 a, v3 b)
{
    return mk(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
static v3 norm(v3 a)
{
    float l = sqrtf(dot(a, a));
    return l > 0 ? scl(a, 1.0f / l) : mk(0, 1, 0);
}

static uint32_t vert(mesh_b *b, v3 p, v3 n, float u, float v)
{
    if (b->oom) return 0;
    if (b->nv == b->cv) {
        uint32_t nc = b->cv ? b->cv * 2 : 1024;
        pg_vertex *nvp = realloc(b->v, sizeof(pg_vertex) * nc);
        if (!nvp) {
            b->oom = true;
            return 0;
        }
        b->v = nvp;
        b->cv = nc;
    }
    pg_vertex *x = &b->v[b->nv];
    memset(x, 0, sizeof *x);
    x->position[0] = p.x;
    x->position[1] = p.y;
    x->position[2] = p.z;
    x->normal[0] = n.x;
    x->normal[1] = n.y;
    x->normal[2] = n.z;
    x->uv[0] = u;
    x->uv[1] = v;
    return b->nv++;
}

/* Emits a triangle wound CCW as seen from the side its vertex normals point to. */
static void tri(mesh_b *b, uint32_t i0, uint32_t i1, uint32_t i2)
{
    if (b->oom) return;
    if (b->ni + 3 > b->ci) {
        uint32_t nc = b->ci ? b->ci * 2 : 4096;
        uint32_t *np = realloc(b->idx, sizeof(uint32_t) * nc);
        if (!np) {
            b->oom = true;
            return;
        }
        b->idx = np;
        b->ci = nc;
    }
    const pg_vertex *a = &b->v[i0], *c1 = &b->v[i1], *c2 = &b->v[i2];
    v3 pa = mk(a->position[0], a->position[1], a->position[2]);
    v3 e1 = sub(mk(c1->position[0], c1->position[1], c1->position[2]), pa);
    v3 e2 = sub(mk(c2->position[0], c2->position[1], c2->position[2]), pa);
    v3 fn = cross(e1, e2);
    v3 vn = mk(a->normal[0] + c1->normal[0] + c2->normal[0], a->normal[1] + c1->normal[1] + c2->normal[1],
               a->normal[2] + c1->normal[2] + c2->normal[2]);
    b->idx[b->ni++] = i0;
    if (dot(fn, vn) >= 0) {
        b->idx[b->ni++] = i1;
        b->idx[b->ni++] = i2;
    } else {
        b->idx[b->ni++] = i2;
        b->idx[b->ni++] = i1;
    }
}

static void quad_idx(mesh_b *b, uint32_t a, uint32_t c, uint32_t d, uint32_t e)
{
    tri(b, a, c, d);
    tri(b, a, d, e);
}

/* Planar UV axes for a face with normal n: u to the right and v down as seen from the front
 * (glTF UV convention: v grows downward in the image); horizontal faces map x/z. */
static void planar_axes(v3 n, float scale, v3 *ua, v3 *va)
{
    float s = 1.0f / scale;
    if (fabsf(n.y) > 0.7f) {
        *ua = mk(n.y > 0 ? s : -s, 0, 0);
        *va = mk(0, 0, s);
    } else {
        v3 right = norm(cross(scl(n, -1.0f), mk(0, 1, 0)));
        *ua = scl(right, s);
        *va = mk(0, -s, 0);
    }
}

/* A planar grid O + U*s + V*t (s, t in 0..1) with nu x nv cells, normal n, world-planar UVs. */
static void grid(mesh_b *b, v3 O, v3 U, v3 V, int nu, int nv, v3 n, float tex_scale)
{
    v3 ua, va;
    planar_axes(n, tex_scale, &ua, &va);
    uint32_t base = b->nv;
    for (int j = 0; j <= nv; j++)
        for (int i = 0; i <= nu; i++) {
            v3 p = add(O, add(scl(U, (float)i / nu), scl(V, (float)j / nv)));
            vert(b, p, n, dot(p, ua), dot(p, va));
        }
    for (int j = 0; j < nv; j++)
        for (int i = 0; i < nu; i++) {
            uint32_t a = base + (uint32_t)(j * (nu + 1) + i);
            quad_idx(b, a, a + 1, a + 1 + (uint32_t)(nu + 1), a + (uint32_t)(nu + 1));
        }
}

/* Axis-aligned box, outward faces; skip_mask bits: 1 -x, 2 +x, 4 -y, 8 +y, 16 -z, 32 +z. */
static void box(mesh_b *b, v3 mn, v3 mx, unsigned skip_mask, float tex_scale)
{
    v3 d = sub(mx, mn);
    if (!(skip_mask & 1)) grid(b, mn, mk(0, d.y, 0), mk(0, 0, d.z), 1, 1, mk(-1, 0, 0), tex_scale);
    if (!(skip_mask & 2))
        grid(b, mk(mx.x, mn.y, mn.z), mk(0, d.y, 0), mk(0, 0, d.z), 1, 1, mk(1, 0, 0), tex_scale);
    if (!(skip_mask & 4)) grid(b, mn, mk(d.x, 0, 0), mk(0, 0, d.z), 1, 1, mk(0, -1, 0), tex_scale);
    if (!(skip_mask & 8))
        grid(b, mk(mn.x, mx.y, mn.z), mk(d.x, 0, 0), mk(0, 0, d.z), 1, 1, mk(0, 1, 0), tex_scale);
    if (!(skip_mask & 16)) grid(b, mn, mk(d.x, 0, 0), mk(0, d.y, 0), 1, 1, mk(0, 0, -1), tex_scale);
    if (!(skip_mask & 32))
        grid(b, mk(mn.x, mn.y, mx.z), mk(d.x, 0, 0), mk(0, d.y, 0), 1, 1, mk(0, 0, 1), tex_scale);
}

/* Surface of revolution around the vertical axis through (cx, cz) from a profile of (r, y)
 * points listed bottom to top. Normals are smooth around the axis and smooth along the profile
 * where neighbouring segments bend by less than ~40 degrees (creases elsewhere). */
static void lathe(mesh_b *b, float cx, float cz, const float (*prof)[2], int np, int segs,
                  float tex_scale)
{
    float rmax = 0;
    for (int k = 0; k < np; k++) rmax = fmaxf(rmax, prof[k][0]);
    float u_rep = roundf(2.0f * PI_F * rmax / tex_scale);
    if (u_rep < 1) u_rep = 1;
    float arc = 0;
    for (int k = 0; k + 1 < np; k++) {
        float dr = prof[k + 1][0] - prof[k][0], dy = prof[k + 1][1] - prof[k][1];
        float len = sqrtf(dr * dr + dy * dy);
        if (len <= 0) continue;
        /* profile-plane normal of this segment: (dy, -dr) / len in (r, y) */
        float sn[2] = {dy / len, -dr / len};
        float nb[2] = {sn[0], sn[1]}, nt[2] = {sn[0], sn[1]};
        if (k > 0) {
            float pr = prof[k][0] - prof[k - 1][0], py = prof[k][1] - prof[k - 1][1];
            float pl = sqrtf(pr * pr + py * py);
            if (pl > 0) {
                float pn[2] = {py / pl, -pr / pl};
                if (pn[0] * sn[0] + pn[1] * sn[1] > 0.766f) {
                    float m0 = pn[0] + sn[0], m1 = pn[1] + sn[1], ml = sqrtf(m0 * m0 + m1 * m1);
                    nb[0] = m0 / ml;
                    nb[1] = m1 / ml;
                }
            }
        }
        if (k + 2 < np) {
            float qr = prof[k + 2][0] - prof[k + 1][0], qy = prof[k + 2][1] - prof[k + 1][1];
            float ql = sqrtf(qr * qr + qy * qy);
            if (ql > 0) {
                float qn[2] = {qy / ql, -qr / ql};
                if (qn[0] * sn[0] + qn[1] * sn[1] > 0.766f) {
                    float m0 = qn[0] + sn[0], m1 = qn[1] + sn[1], ml = sqrtf(m0 * m0 + m1 * m1);
                    nt[0] = m0 / ml;
                    nt[1] = m1 / ml;
                }
            }
        }
        uint32_t base = b->nv;
        for (int s = 0; s <= segs; s++) {
            float th = 2.0f * PI_F * (float)(s % segs) / (float)segs;
            float c = cosf(th), sn_ = sinf(th);
            float u = u_rep * (float)s / (float)segs;
            for (int e = 0; e < 2; e++) {
                float r = prof[k + e][0], y = prof[k + e][1];
                const float *nn = e ? nt : nb;
                v3 p = mk(cx + r * c, y, cz + r * sn_);
                v3 n = norm(mk(nn[0] * c, nn[1], nn[0] * sn_));
                float a = arc + (e ? len : 0);
                vert(b, p, n, u, -a / tex_scale);
            }
        }
        for (int s = 0; s < segs; s++) {
            uint32_t a = base + (uint32_t)s * 2;
            quad_idx(b, a, a + 2, a + 3, a + 1);
        }
        arc += len;
    }
}

/* One arcade bay: a wall slab between x0 and x0 + BAY, y from y0 (springing) to y1, thickness
 * WALL_T centred on z = zc, pierced by a semicircular arch of radius r centred at (x0+BAY/2, y0).
 * Emits both faces of the spandrel (strips between the arch and the rectangle along rays from the
 * arch centre, with the rectangle's top corners included) and the intrados. */
static void arch_bay(mesh_b *b, float x0, float y0, float y1, float r, float zc, int nseg,
                     float tex_scale)
{
    const float hs = BAY * 0.5f, xc = x0 + hs;
    float th_c = atan2f(y1 - y0, hs); /* ray through the top-right corner */
    float th[80];
    int n = 0;
    for (int i = 0; i <= nseg && n < 78; i++) {
        float t = PI_F * (float)i / (float)nseg;
        /* insert the corner rays in order */
        if (n > 0 && th[n - 1] < th_c && t > th_c) th[n++] = th_c;
        if (n > 0 && th[n - 1] < PI_F - th_c && t > PI_F - th_c) th[n++] = PI_F - th_c;
        th[n++] = t;
    }
    for (int side = -1; side <= 1; side += 2) {
        float z = zc + side * WALL_T * 0.5f;
        v3 nrm = mk(0, 0, (float)side);
        v3 ua, va;
        planar_axes(nrm, tex_scale, &ua, &va);
        uint32_t base = b->nv;
        for (int i = 0; i < n; i++) {
            float c = cosf(th[i]), s = sinf(th[i]);
            v3 pa = mk(xc + r * c, y0 + r * s, z);
            /* ray to the rectangle [xc-hs, xc+hs] x [y0, y1] */
            float tx = fabsf(c) > 1e-6f ? hs / fabsf(c) : 1e30f;
            float ty = s > 1e-6f ? (y1 - y0) / s : 1e30f;
            float t = fminf(tx, ty);
            v3 pq = mk(xc + t * c, y0 + t * s, z);
            if (i == 0) pq = mk(xc + hs, y0, z);
            if (i == n - 1) pq = mk(xc - hs, y0, z);
            vert(b, pa, nrm, dot(pa, ua), dot(pa, va));
            vert(b, pq, nrm, dot(pq, ua), dot(pq, va));
        }
        for (int i = 0; i + 1 < n; i++) {
            uint32_t a = base + (uint32_t)i * 2;
            quad_idx(b, a, a + 2, a + 3, a + 1);
        }
    }
    /* intrados: normals point to the arch centre; u along the arc, v across the wall */
    const int nd = 2;
    uint32_t base = b->nv;
    for (int i = 0; i <= nseg; i++) {
        float t = PI_F * (float)i / (float)nseg;
        float c = cosf(t), s = sinf(t);
        for (int k = 0; k <= nd; k++) {
            float z = zc - WALL_T * 0.5f + WALL_T * (float)k / nd;
            vert(b, mk(xc + r * c, y0 + r * s, z), mk(-c, -s, 0), r * t / tex_scale, z / tex_scale);
        }
    }
    for (int i = 0; i < nseg; i++)
        for (int k = 0; k < nd; k++) {
            uint32_t a = base + (uint32_t)(i * (nd + 1) + k);
            quad_idx(b, a, a + 1, a + 1 + (uint32_t)(nd + 1), a + (uint32_t)(nd + 1));
        }
}

/* A full arcade row at z = zc: columns, arches, wall ends. s scales the column (1 lower, 0.6
 * upper), ybase is the floor it stands on, ytop the top of its wall. */
static void arcade(mesh_b *m, float zc, float ybase, float s, float ytop, int segs)
{
    /* column profile (r, y) for s = 1, y from the plinth top (0.3) to the abacus (4.0) */
    static const float prof[][2] = {
        {0.44f, 0.30f}, {0.465f, 0.34f}, {0.455f, 0.39f}, {0.42f, 0.43f}, {0.38f, 0.455f},
        {0.36f, 0.50f}, {0.355f, 1.2f},  {0.35f, 1.9f},   {0.34f, 2.6f},  {0.325f, 3.3f},
        {0.31f, 3.60f}, {0.36f, 3.60f},  {0.36f, 3.70f},  {0.31f, 3.70f}, {0.33f, 3.76f},
        {0.38f, 3.84f}, {0.45f, 3.91f},  {0.51f, 3.96f},  {0.53f, 4.0f},
    };
    enum { NP = sizeof prof / sizeof prof[0] };
    float p[NP][2];
    const float plinth = 0.45f * s, abacus = 0.55f * s;
    const float y_abacus0 = ybase + 4.0f * s, y0 = ybase + 4.3f * s;
    for (int i = 0; i < N_COLS; i++) {
        float x = COL_X0 + BAY * (float)i;
        for (int k = 0; k < NP; k++) {
            p[k][0] = prof[k][0] * s;
            p[k][1] = ybase + prof[k][1] * s;
        }
        box(&m[MAT_STONE], mk(x - plinth, ybase, zc - plinth), mk(x + plinth, ybase + 0.3f * s, zc + plinth),
            4, TS_STONE);
        lathe(&m[MAT_MARBLE], x, zc, (const float(*)[2])p, NP, segs, TS_MARBLE);
        box(&m[MAT_STONE], mk(x - abacus, y_abacus0, zc - abacus), mk(x + abacus, y0, zc + abacus), 0,
            TS_STONE);
    }
    float r = BAY * 0.5f - abacus;
    for (int i = 0; i + 1 < N_COLS; i++)
        arch_bay(&m[MAT_STONE], COL_X0 + BAY * (float)i, y0, ytop, r, zc, 32, TS_STONE);
    /* wall ends beyond the first and last column centres */
    float xe0 = COL_X0 - abacus, xe1 = COL_X0 + BAY * (N_COLS - 1) + abacus;
    box(&m[MAT_STONE], mk(xe0, y0, zc - WALL_T * 0.5f), mk(COL_X0, ytop, zc + WALL_T * 0.5f), 2 | 4 | 8,
        TS_STONE);
    box(&m[MAT_STONE], mk(COL_X0 + BAY * (N_COLS - 1), y0, zc - WALL_T * 0.5f),
        mk(xe1, ytop, zc + WALL_T * 0.5f), 1 | 4 | 8, TS_STONE);
}

/* A drape hanging in the plane z = zc (facing -side*z toward the nave), x in [x0, x1],
 * y from ytop down to ybot, with waves growing toward the bottom. */
static void drape(mesh_b *b, float x0, float x1, float ybot, float ytop, float zc, float side)
{
    const int nu = 24, nv = 12;
    const float k = 2.0f * PI_F / 0.55f, a0 = 0.03f, a1 = 0.035f;
    uint32_t base = b->nv;
    for (int j = 0; j <= nv; j++)
        for (int i = 0; i <= nu; i++) {
            float x = x0 + (x1 - x0) * (float)i / nu;
            float y = ytop - (ytop - ybot) * (float)j / nv;
            float A = a0 + a1 * (ytop - y);
            float w = sinf(k * (x - x0));
            float z = zc + A * w;
            float dzdx = A * k * cosf(k * (x - x0)), dzdy = -a1 * w;
            v3 n = norm(mk(dzdx * side, dzdy * side, -side));
            vert(b, mk(x, y, z), n, (x - x0) / 1.0f, (ytop - y) / 1.0f);
        }
    for (int j = 0; j < nv; j++)
        for (int i = 0; i < nu; i++) {
            uint32_t a = base + (uint32_t)(j * (nu + 1) + i);
            quad_idx(b, a, a + 1, a + 1 + (uint32_t)(nu + 1), a + (uint32_t)(nu + 1));
        }
}

static void build_geometry(mesh_b *m)
{
    /* room shell: floor, walls, ceiling (all facing inward) */
    grid(&m[MAT_FLOOR], mk(-HX, 0, -HZ), mk(2 * HX, 0, 0), mk(0, 0, 2 * HZ), 60, 30, mk(0, 1, 0),
         TS_FLOOR);
    grid(&m[MAT_CEILING], mk(-HX, ROOM_H, -HZ), mk(2 * HX, 0, 0), mk(0, 0, 2 * HZ), 30, 15,
         mk(0, -1, 0), 1.0f);
    grid(&m[MAT_BRICK], mk(-HX, 0, -HZ), mk(2 * HX, 0, 0), mk(0, ROOM_H, 0), 30, 12, mk(0, 0, 1),
         TS_BRICK);
    grid(&m[MAT_BRICK], mk(-HX, 0, HZ), mk(2 * HX, 0, 0), mk(0, ROOM_H, 0), 30, 12, mk(0, 0, -1),
         TS_BRICK);
    grid(&m[MAT_BRICK], mk(-HX, 0, -HZ), mk(0, 0, 2 * HZ), mk(0, ROOM_H, 0), 15, 12, mk(1, 0, 0),
         TS_BRICK);
    grid(&m[MAT_BRICK], mk(HX, 0, -HZ), mk(0, 0, 2 * HZ), mk(0, ROOM_H, 0), 15, 12, mk(-1, 0, 0),
         TS_BRICK);

    for (int side = -1; side <= 1; side += 2) {
        float zc = ROW_Z * (float)side;
        /* lower arcade up to the gallery slab */
        arcade(m, zc, 0.0f, 1.0f, SLAB_Y0, 32);
        /* gallery slab over the aisle: z from the arcade's nave face - 0.1 to the outer wall */
        float zin = zc - side * (WALL_T * 0.5f + 0.1f), zout = HZ * (float)side;
        float za = fminf(zin, zout), zb = fmaxf(zin, zout);
        grid(&m[MAT_FLOOR], mk(-HX, SLAB_Y1, za), mk(2 * HX, 0, 0), mk(0, 0, zb - za), 30, 4,
             mk(0, 1, 0), TS_FLOOR);
        grid(&m[MAT_STONE], mk(-HX, SLAB_Y0, za), mk(2 * HX, 0, 0), mk(0, 0, zb - za), 30, 4,
             mk(0, -1, 0), TS_STONE);
        grid(&m[MAT_STONE], mk(-HX, SLAB_Y0, zin), mk(2 * HX, 0, 0), mk(0, SLAB_Y1 - SLAB_Y0, 0), 30,
             1, mk(0, 0, -(float)side), TS_STONE);
        /* upper arcade on the gallery, its wall up to the ceiling */
        arcade(m, zc, SLAB_Y1, UPPER_SCALE, ROOM_H, 24);
        /* grilles between the upper columns (one double-sided quad per bay) */
        float ph = 0.45f * UPPER_SCALE;
        for (int i = 0; i + 1 < N_COLS; i++) {
            float x0 = COL_X0 + BAY * (float)i + ph, x1 = COL_X0 + BAY * (float)(i + 1) - ph;
            grid(&m[MAT_GRILLE], mk(x0, SLAB_Y1, zc), mk(x1 - x0, 0, 0), mk(0, 1.0f, 0), 1, 1,
                 mk(0, 0, -(float)side), TS_GRILLE);
        }
        /* drapes hanging from the gallery edge in alternate bays */
        for (int i = 1; i + 1 < N_COLS; i += 2) {
            float xm = COL_X0 + BAY * ((float)i + 0.5f);
            drape(&m[MAT_DRAPE], xm - 0.9f, xm + 0.9f, 2.8f, SLAB_Y1,
                  zin - side * 0.05f, (float)side);
        }
    }
}

/* ------------------------------------------------------------------------------------------ */
/* procedural textures                                                                         */

static uint32_t hash3(uint32_t x, uint32_t y, uint32_t z)
{
    uint32_t h = x * 0x8da6b343u ^ y * 0xd8163841u ^ z * 0xcb1ab31fu;
    h ^= h >> 16;
    h *= 0x7feb352du;
    h ^= h >> 15;
    h *= 0x846ca68bu;
    h ^= h >> 16;
    return h;
}
static float hashf(uint32_t x, uint32_t y, uint32_t z) { return (float)(hash3(x, y, z) >> 8) / 16777216.0f; }

/* periodic value noise: lattice of `period` cells, x, y in cell units */
static float vnoise(float x, float y, int period, uint32_t seed)
{
    float fx = floorf(x), fy = floorf(y);
    int ix = (int)fx, iy = (int)fy;
    float tx = x - fx, ty = y - fy;
    tx = tx * tx * (3 - 2 * tx);
    ty = ty * ty * (3 - 2 * ty);
    int x0 = ((ix % period) + period) % period, y0 = ((iy % period) + period) % period;
    int x1 = (x0 + 1) % period, y1 = (y0 + 1) % period;
    float a = hashf((uint32_t)x0, (uint32_t)y0, seed), b = hashf((uint32_t)x1, (uint32_t)y0, seed);
    float c = hashf((uint32_t)x0, (uint32_t)y1, seed), d = hashf((uint32_t)x1, (uint32_t)y1, seed);
    return (a + (b - a) * tx) + ((c + (d - c) * tx) - (a + (b - a) * tx)) * ty;
}

/* fractal noise over a size x size texture, tileable; returns ~0..1 */
static float fbm(int px, int py, int size, int base_period, int octaves, uint32_t seed)
{
    float sum = 0, amp = 0.5f, tot = 0;
    int period = base_period;
    for (int o = 0; o < octaves; o++) {
        float f = (float)period / (float)size;
        sum += amp * vnoise((float)px * f, (float)py * f, period, seed + (uint32_t)o * 101u);
        tot += amp;
        amp *= 0.5f;
        period *= 2;
    }
    return sum / tot;
}

static uint8_t to_u8(float v)
{
    if (!(v > 0)) return 0;
    if (v >= 1) return 255;
    return (uint8_t)(v * 255.0f + 0.5f);
}

static void put(uint8_t *img, int size, int x, int y, float r, float g, float b, float a)
{
    uint8_t *p = img + ((size_t)y * size + x) * 4;
    p[0] = to_u8(r);
    p[1] = to_u8(g);
    p[2] = to_u8(b);
    p[3] = to_u8(a);
}

/* tangent-space normal map from a tileable height field (x right, y down the image; green = up,
 * the glTF convention) */
static void height_to_normal(const float *h, int size, float strength, uint8_t *out)
{
    for (int y = 0; y < size; y++)
        for (int x = 0; x < size; x++) {
            int xl = (x + size - 1) % size, xr = (x + 1) % size;
            int yu = (y + size - 1) % size, yd = (y + 1) % size;
            float dx = (h[y * size + xr] - h[y * size + xl]) * 0.5f;
            float dy = (h[yd * size + x] - h[yu * size + x]) * 0.5f;
            v3 n = norm(mk(-strength * dx, strength * dy, 1.0f));
            put(out, size, x, y, n.x * 0.5f + 0.5f, n.y * 0.5f + 0.5f, n.z * 0.5f + 0.5f, 1.0f);
        }
}

/* floor: 4 x 4 checker of 0.5 m tiles (cream / dark red marble) with grout */
static void tex_floor(int S, uint8_t *rgb, float *h)
{
    const int tile = S / 4, grout = S / 128;
    for (int y = 0; y < S; y++)
        for (int x = 0; x < S; x++) {
            int tx = x / tile, ty = y / tile, lx = x % tile, ly = y % tile;
            int ex = lx < tile - 1 - lx ? lx : tile - 1 - lx;
            int ey = ly < tile - 1 - ly ? ly : tile - 1 - ly;
            int e = ex < ey ? ex : ey; /* distance to the tile edge in texels */
            float n = fbm(x, y, S, 8, 4, 11);
            float vein = fabsf(sinf(((float)x + (float)y) * 6.0f * PI_F / (float)S + 5.0f * n));
            float r, g, b;
            if ((tx + ty) & 1) {
                r = 0.50f;
                g = 0.20f;
                b = 0.15f;
            } else {
                r = 0.86f;
                g = 0.81f;
                b = 0.70f;
            }
            float v = 0.85f + 0.15f * powf(vein, 0.3f) + 0.08f * (hashf((uint32_t)tx, (uint32_t)ty, 3) - 0.5f);
            r *= v;
            g *= v;
            b *= v;
            float hh = 1.0f;
            if (e < grout) {
                r = g = b = 0.33f + 0.05f * n;
                hh = 0.0f;
            } else if (e < grout + 4) {
                hh = (float)(e - grout + 1) / 5.0f;
            }
            put(rgb, S, x, y, r, g, b, 1.0f);
            h[y * S + x] = hh * 3.0f + 0.4f * n;
        }
}

/* bricks: running bond, 64 x 32 texel bricks (0.25 x 0.125 m at 512 / 2 m), 4-texel mortar */
static void tex_brick(int S, uint8_t *rgb, float *h)
{
    const int bw = S / 8, bh = S / 16, mortar = S / 128;
    for (int y = 0; y < S; y++)
        for (int x = 0; x < S; x++) {
            int row = y / bh, ly = y % bh;
            int xs = x + ((row & 1) ? bw / 2 : 0);
            int col = (xs / bw) % (S / bw), lx = xs % bw;
            int ex = lx < bw - 1 - lx ? lx : bw - 1 - lx;
            int ey = ly < bh - 1 - ly ? ly : bh - 1 - ly;
            int e = ex < ey ? ex : ey;
            float n = fbm(x, y, S, 16, 4, 23);
            float hb = hashf((uint32_t)col, (uint32_t)row, 7);
            float r = 0.55f + 0.15f * hb, g = 0.27f + 0.08f * hb, b = 0.18f + 0.05f * hb;
            float v = 0.8f + 0.3f * n;
            r *= v;
            g *= v;
            b *= v;
            float hh = 1.0f;
            if (e < mortar) {
                r = 0.70f * (0.9f + 0.2f * n);
                g = 0.68f * (0.9f + 0.2f * n);
                b = 0.62f * (0.9f + 0.2f * n);
                hh = 0.0f;
            } else if (e < mortar + 3) {
                hh = (float)(e - mortar + 1) / 4.0f;
            }
            put(rgb, S, x, y, r, g, b, 1.0f);
            h[y * S + x] = hh * 2.5f + 0.8f * n;
        }
}

/* stone: ashlar blocks 1 m x 0.5 m (at 256 / 2 m), sandstone */
static void tex_stone(int S, uint8_t *rgb)
{
    const int bw = S / 2, bh = S / 4, joint = 2;
    for (int y = 0; y < S; y++)
        for (int x = 0; x < S; x++) {
            int row = y / bh, ly = y % bh;
            int xs = x + ((row & 1) ? bw / 2 : 0);
            int col = (xs / bw) % 2, lx = xs % bw;
            float n = fbm(x, y, S, 8, 5, 37);
            float hb = hashf((uint32_t)col, (uint32_t)row, 9);
            float v = 0.85f + 0.2f * n + 0.08f * hb;
            float r = 0.78f * v, g = 0.70f * v, b = 0.56f * v;
            if (lx < joint || ly < joint) {
                r *= 0.6f;
                g *= 0.6f;
                b *= 0.6f;
            }
            put(rgb, S, x, y, r, g, b, 1.0f);
        }
}

/* marble: white with grey veins (turbulent sine) */
static void tex_marble(int S, uint8_t *rgb)
{
    for (int y = 0; y < S; y++)
        for (int x = 0; x < S; x++) {
            float n = fbm(x, y, S, 4, 6, 53);
            float t = fabsf(sinf(((float)x * 2.0f + (float)y) * 2.0f * PI_F / (float)S + 9.0f * n));
            float v = 0.62f + 0.38f * powf(t, 0.25f);
            put(rgb, S, x, y, 0.93f * v, 0.91f * v, 0.87f * v, 1.0f);
        }
}

/* grille: diagonal lattice bars (alpha 1) with holes (alpha 0); the holes keep the bar colour so
 * mip filtering does not darken the edges */
static void tex_grille(int S, uint8_t *rgb)
{
    const float cell = (float)S / 4.0f, half_bar = (float)S / 48.0f;
    for (int y = 0; y < S; y++)
        for (int x = 0; x < S; x++) {
            float a = fmodf((float)(x + y) + 0.5f, cell), b = fmodf((float)(x - y + S) + 0.5f, cell);
            float da = fminf(a, cell - a), db = fminf(b, cell - b);
            /* frame along the texture's top and bottom (the grille's rails) */
            int fy = y < S - 1 - y ? y : S - 1 - y;
            bool bar = da < half_bar || db < half_bar || fy < S / 24;
            float n = fbm(x, y, S, 8, 3, 71);
            float v = 0.8f + 0.4f * n;
            put(rgb, S, x, y, 0.42f * v, 0.30f * v, 0.14f * v, bar ? 1.0f : 0.0f);
        }
}

/* ------------------------------------------------------------------------------------------ */

static void set_material(pg_material *m, const char *name, float r, float g, float b, int tex,
                         int ntex, float spec, float shin)
{
    pg_material_init(m, name);
    m->base_color[0] = r;
    m->base_color[1] = g;
    m->base_color[2] = b;
    m->base_color[3] = 1.0f;
    m->base_color_tex = tex;
    m->normal_tex = ntex;
    m->normal_scale = 1.0f;
    m->alpha_mode = PG_ALPHA_OPAQUE;
    m->alpha_cutoff = 0.5f;
    m->specular = spec;
    m->shininess = shin;
}

enum { TEX_FLOOR, TEX_FLOOR_N, TEX_BRICK, TEX_BRICK_N, TEX_STONE, TEX_MARBLE, TEX_GRILLE, TEX_COUNT };

static pg_result make_textures(pg_scene *s, pg_error *err)
{
    const int S512 = 512, S256 = 256, S128 = 128;
    uint8_t *rgb = malloc((size_t)S512 * S512 * 4);
    uint8_t *nrm = malloc((size_t)S512 * S512 * 4);
    float *h = malloc(sizeof(float) * (size_t)S512 * S512);
    s->textures = calloc(TEX_COUNT, sizeof(pg_texture));
    pg_result r = PG_OK;
    if (!rgb || !nrm || !h || !s->textures) {
        r = pg_fail(err, PG_ERR_OOM, "default scene: out of memory for textures");
        goto done;
    }
#define ADD(nm, px, sz, srgb)                                                                      \
    do {                                                                                           \
        r = pg_texture_init(&s->textures[s->n_textures], nm, px, sz, sz, srgb, err);              \
        if (r != PG_OK) goto done;                                                                 \
        s->n_textures++;                                                                           \
    } while (0)
    tex_floor(S512, rgb, h);
    height_to_normal(h, S512, 1.5f, nrm);
    ADD("floor_tiles", rgb, S512, true);
    ADD("floor_tiles_normal", nrm, S512, false);
    tex_brick(S512, rgb, h);
    height_to_normal(h, S512, 1.5f, nrm);
    ADD("brick", rgb, S512, true);
    ADD("brick_normal", nrm, S512, false);
    tex_stone(S256, rgb);
    ADD("stone", rgb, S256, true);
    tex_marble(S256, rgb);
    ADD("marble", rgb, S256, true);
    tex_grille(S128, rgb);
    ADD("grille", rgb, S128, true);
#undef ADD
done:
    free(rgb);
    free(nrm);
    free(h);
    return r;
}

pg_result pg_scene_create_default(pg_scene **out, pg_error *err)
{
    if (!out) return pg_fail(err, PG_ERR_INVALID_ARG, "pg_scene_create_default: out is NULL");
    *out = NULL;
    pg_scene *s = calloc(1, sizeof *s);
    mesh_b m[MAT_COUNT];
    memset(m, 0, sizeof m);
    pg_result r = PG_OK;
    if (!s) return pg_fail(err, PG_ERR_OOM, "default scene: out of memory");
    pg_strlcpy(s->name, "default", sizeof s->name);
    pg_strlcpy(s->path, "default", sizeof s->path);

    build_geometry(m);
    uint32_t nv = 0, ni = 0;
    for (int k = 0; k < MAT_COUNT; k++) {
        if (m[k].oom) {
            r = pg_fail(err, PG_ERR_OOM, "default scene: out of memory for geometry");
            goto fail;
        }
        pg_mesh_compute_tangents(m[k].v, m[k].nv, m[k].idx, m[k].ni);
        nv += m[k].nv;
        ni += m[k].ni;
    }

    s->vertices = malloc(sizeof(pg_vertex) * nv);
    s->indices = malloc(sizeof(uint32_t) * ni);
    s->primitives = calloc(MAT_COUNT, sizeof(pg_primitive));
    s->materials = calloc(MAT_COUNT, sizeof(pg_material));
    if (!s->vertices || !s->indices || !s->primitives || !s->materials) {
        r = pg_fail(err, PG_ERR_OOM, "default scene: out of memory");
        goto fail;
    }
    for (int k = 0; k < MAT_COUNT; k++) {
        pg_primitive *p = &s->primitives[s->n_primitives++];
        p->first_index = s->n_indices;
        p->index_count = m[k].ni;
        p->vertex_offset = (int32_t)s->n_vertices;
        p->material = (uint32_t)k;
        memcpy(s->vertices + s->n_vertices, m[k].v, sizeof(pg_vertex) * m[k].nv);
        memcpy(s->indices + s->n_indices, m[k].idx, sizeof(uint32_t) * m[k].ni);
        s->n_vertices += m[k].nv;
        s->n_indices += m[k].ni;
    }

    r = make_textures(s, err);
    if (r != PG_OK) goto fail;

    pg_material *mt = s->materials;
    set_material(&mt[MAT_FLOOR], "floor_tiles", 1, 1, 1, TEX_FLOOR, TEX_FLOOR_N, 0.35f, 48.0f);
    set_material(&mt[MAT_BRICK], "brick", 1, 1, 1, TEX_BRICK, TEX_BRICK_N, 0.05f, 6.0f);
    set_material(&mt[MAT_STONE], "stone", 1, 1, 1, TEX_STONE, -1, 0.08f, 10.0f);
    set_material(&mt[MAT_MARBLE], "marble", 1, 1, 1, TEX_MARBLE, -1, 0.6f, 96.0f);
    set_material(&mt[MAT_CEILING], "ceiling_plain", 0.82f, 0.78f, 0.70f, -1, -1, 0.04f, 2.0f);
    set_material(&mt[MAT_GRILLE], "bronze_grille", 1, 1, 1, TEX_GRILLE, -1, 0.5f, 40.0f);
    mt[MAT_GRILLE].alpha_mode = PG_ALPHA_MASK;
    mt[MAT_GRILLE].alpha_cutoff = 0.5f;
    mt[MAT_GRILLE].double_sided = true;
    set_material(&mt[MAT_DRAPE], "red_drape", 0.55f, 0.06f, 0.05f, -1, -1, 0.03f, 2.0f);
    mt[MAT_DRAPE].double_sided = true;
    s->n_materials = MAT_COUNT;

    pg_scene_finalize(s);
    for (int k = 0; k < MAT_COUNT; k++) {
        free(m[k].v);
        free(m[k].idx);
    }
    *out = s;
    return PG_OK;

fail:
    for (int k = 0; k < MAT_COUNT; k++) {
        free(m[k].v);
        free(m[k].idx);
    }
    pg_scene_free(s);
    return r;
}
