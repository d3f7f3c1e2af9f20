/* Embree's side of make bench-embree (issue 28): the reference that
   raytrace's mesh rays are measured against, one thread.

   embree_rays [--robust] [--compare MASK] [--shadows SHADOW_RAYS SHADOW_MASK_OUT
               [--compare-shadows MASK]] OBJ RAYS MASK_OUT

   Reads the triangles of a Wavefront OBJ file (v and f lines; polygons as
   fans, as raytrace reads them), builds Embree's scene on one thread
   (RTC_SCENE_FLAG_ROBUST with --robust), casts the rays of the file RAYS
   (six little-endian float64s per ray, origin then direction, written by
   raytrace_rays from raytrace's own camera rays) with the range (1, inf),
   writes the hit mask (one byte per ray, 1 for a hit) to MASK_OUT. With
   --shadows it casts the shadow rays of SHADOW_RAYS (the same format,
   written by raytrace_rays from raytrace's hits) with rtcOccluded1 and the
   range (0, 1), camera rays / shadow rays times over (at least once, as
   Mesh_rays.rounds), and writes their mask (1: blocked) to SHADOW_MASK_OUT.
   It prints one row, the columns of raytrace_rays's: read and build CPU
   seconds (the build: the geometry's buffers filled and the scene
   committed), the commit alone (the hierarchy's build), ns per camera ray
   (CPU time) twice (Embree shades nothing), the share of rays that hit,
   peak RSS per triangle in bytes, with --compare the number of rays whose
   hit differs from the mask MASK; then with --shadows the ns per shadow
   ray, the share blocked and, with --compare-shadows, the number that
   differ from that mask ("-" where not asked). Embree takes floats: the
   vertices and rays are rounded to them. */

#include <embree3/rtcore.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>

static double cpu(void) {
  struct timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static void die(const char *what, const char *why) {
  fprintf(stderr, "embree_rays: %s: %s\n", what, why);
  exit(1);
}

static char *slurp(const char *path, size_t *len) {
  FILE *f = fopen(path, "rb");
  if (!f) die(path, "cannot open");
  fseek(f, 0, SEEK_END);
  long n = ftell(f);
  fseek(f, 0, SEEK_SET);
  char *b = malloc((size_t)n + 1);
  if (!b || fread(b, 1, (size_t)n, f) != (size_t)n) die(path, "cannot read");
  b[n] = '\0';
  fclose(f);
  *len = (size_t)n;
  return b;
}

/* Growable arrays of the OBJ's vertices (floats) and triangles. */
typedef struct { float *v; size_t nv, cv; unsigned *t; size_t nt, ct; } mesh;

static void push_vertex(mesh *m, float x, float y, float z) {
  if (m->nv == m->cv) { m->cv = m->cv ? 2 * m->cv : 1024; m->v = realloc(m->v, 3 * m->cv * sizeof(float)); }
  m->v[3 * m->nv] = x; m->v[3 * m->nv + 1] = y; m->v[3 * m->nv + 2] = z;
  m->nv++;
}

static void push_triangle(mesh *m, long a, long b, long c) {
  if (m->nt == m->ct) { m->ct = m->ct ? 2 * m->ct : 1024; m->t = realloc(m->t, 3 * m->ct * sizeof(unsigned)); }
  m->t[3 * m->nt] = (unsigned)a; m->t[3 * m->nt + 1] = (unsigned)b; m->t[3 * m->nt + 2] = (unsigned)c;
  m->nt++;
}

static void read_obj(const char *path, mesh *m) {
  size_t len;
  char *text = slurp(path, &len), *p = text, *end = text + len;
  while (p < end) {
    char *eol = memchr(p, '\n', (size_t)(end - p));
    if (!eol) eol = end;
    *eol = '\0';
    while (*p == ' ' || *p == '\t') p++;
    if (p[0] == 'v' && (p[1] == ' ' || p[1] == '\t')) {
      char *q = p + 2;
      double x = strtod(q, &q), y = strtod(q, &q), z = strtod(q, &q);
      push_vertex(m, (float)x, (float)y, (float)z);
    } else if (p[0] == 'f' && (p[1] == ' ' || p[1] == '\t')) {
      char *q = p + 2;
      long first = -1, prev = -1, k = 0;
      for (;;) {
        while (*q == ' ' || *q == '\t' || *q == '\r') q++;
        if (*q == '\0') break;
        char *after;
        long i = strtol(q, &after, 10);
        if (after == q) die(path, "bad face");
        q = after;
        while (*q && *q != ' ' && *q != '\t' && *q != '\r') q++; /* /vt/vn */
        long idx = i > 0 ? i - 1 : (long)m->nv + i;
        if (idx < 0 || (size_t)idx >= m->nv) die(path, "face index out of range");
        if (k == 0) first = idx;
        else if (k >= 2) push_triangle(m, first, prev, idx);
        prev = idx;
        k++;
      }
    }
    p = eol + 1;
  }
  free(text);
}

int main(int argc, char **argv) {
  int robust = 0;
  const char *compare = NULL, *shadows = NULL, *shadow_mask = NULL, *compare_shadows = NULL;
  int i = 1;
  for (; i < argc && argv[i][0] == '-' && argv[i][1] == '-'; i++) {
    if (!strcmp(argv[i], "--robust")) robust = 1;
    else if (!strcmp(argv[i], "--compare") && i + 1 < argc) compare = argv[++i];
    else if (!strcmp(argv[i], "--shadows") && i + 2 < argc) { shadows = argv[++i]; shadow_mask = argv[++i]; }
    else if (!strcmp(argv[i], "--compare-shadows") && i + 1 < argc) compare_shadows = argv[++i];
    else die(argv[i], "unknown option");
  }
  if (argc - i != 3) {
    fprintf(stderr, "usage: embree_rays [--robust] [--compare MASK] OBJ RAYS MASK_OUT\n");
    return 2;
  }
  const char *obj = argv[i], *rays_path = argv[i + 1], *mask_path = argv[i + 2];

  double t0 = cpu();
  mesh m = {0};
  read_obj(obj, &m);
  double t1 = cpu();

  RTCDevice dev = rtcNewDevice("threads=1");
  if (!dev) die("rtcNewDevice", "failed");
  RTCScene scene = rtcNewScene(dev);
  rtcSetSceneFlags(scene, robust ? RTC_SCENE_FLAG_ROBUST : RTC_SCENE_FLAG_NONE);
  RTCGeometry g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
  float *vb = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), m.nv);
  unsigned *ib = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), m.nt);
  if (!vb || !ib) die("rtcSetNewGeometryBuffer", "failed");
  memcpy(vb, m.v, 3 * m.nv * sizeof(float));
  memcpy(ib, m.t, 3 * m.nt * sizeof(unsigned));
  free(m.v);
  free(m.t);
  rtcCommitGeometry(g);
  rtcAttachGeometry(scene, g);
  rtcReleaseGeometry(g);
  double t1b = cpu();
  rtcCommitScene(scene);
  double t2 = cpu();
  if (rtcGetDeviceError(dev) != RTC_ERROR_NONE) die("embree", "error building the scene");

  size_t rlen;
  char *raw = slurp(rays_path, &rlen);
  if (rlen % 48) die(rays_path, "not six float64s per ray");
  size_t n = rlen / 48;
  double *r = malloc(rlen);
  memcpy(r, raw, rlen); /* little-endian host assumed, as on x86-64 */
  free(raw);
  unsigned char *mask = malloc(n ? n : 1);

  struct RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  size_t hits = 0;
  double t3 = cpu();
  for (size_t k = 0; k < n; k++) {
    const double *q = r + 6 * k;
    struct RTCRayHit rh;
    rh.ray.org_x = (float)q[0]; rh.ray.org_y = (float)q[1]; rh.ray.org_z = (float)q[2];
    rh.ray.dir_x = (float)q[3]; rh.ray.dir_y = (float)q[4]; rh.ray.dir_z = (float)q[5];
    rh.ray.tnear = 1.0f;
    rh.ray.tfar = INFINITY;
    rh.ray.time = 0.0f;
    rh.ray.mask = 0xFFFFFFFFu;
    rh.ray.id = 0;
    rh.ray.flags = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene, &ctx, &rh);
    int hit = rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
    mask[k] = (unsigned char)hit;
    hits += (size_t)hit;
  }
  double t4 = cpu();

  /* The shadow rays, [rounds] times over, their mask from the first. */
  size_t ns = 0, blocked = 0, rounds = 1;
  unsigned char *smask = NULL;
  double t5 = 0., t6 = 0.;
  if (shadows) {
    size_t slen;
    char *sraw = slurp(shadows, &slen);
    if (slen % 48) die(shadows, "not six float64s per ray");
    ns = slen / 48;
    double *sr = malloc(slen ? slen : 1);
    memcpy(sr, sraw, slen);
    free(sraw);
    smask = malloc(ns ? ns : 1);
    rounds = ns ? n / ns : 1;
    if (rounds < 1) rounds = 1;
    t5 = cpu();
    for (size_t round = 0; round < rounds; round++)
      for (size_t k = 0; k < ns; k++) {
        const double *q = sr + 6 * k;
        struct RTCRay ray;
        ray.org_x = (float)q[0]; ray.org_y = (float)q[1]; ray.org_z = (float)q[2];
        ray.dir_x = (float)q[3]; ray.dir_y = (float)q[4]; ray.dir_z = (float)q[5];
        ray.tnear = 0.0f;
        ray.tfar = 1.0f;
        ray.time = 0.0f;
        ray.mask = 0xFFFFFFFFu;
        ray.id = 0;
        ray.flags = 0;
        rtcOccluded1(scene, &ctx, &ray);
        if (round == 0) {
          int b = ray.tfar < 0.0f; /* -inf where blocked */
          smask[k] = (unsigned char)b;
          blocked += (size_t)b;
        }
      }
    t6 = cpu();
    free(sr);
  }

  struct rusage ru;
  getrusage(RUSAGE_SELF, &ru);
  char differ[32] = "-";
  if (compare) {
    size_t clen;
    char *other = slurp(compare, &clen);
    if (clen != n) die(compare, "not one byte per ray");
    size_t d = 0;
    for (size_t k = 0; k < n; k++) d += (other[k] != 0) != (mask[k] != 0);
    snprintf(differ, sizeof differ, "%zu", d);
    free(other);
  }
  char sdiffer[32] = "-";
  if (compare_shadows && shadows) {
    size_t clen;
    char *other = slurp(compare_shadows, &clen);
    if (clen != ns) die(compare_shadows, "not one byte per shadow ray");
    size_t d = 0;
    for (size_t k = 0; k < ns; k++) d += (other[k] != 0) != (smask[k] != 0);
    snprintf(sdiffer, sizeof sdiffer, "%zu", d);
    free(other);
  }
  double per_ray = n ? (t4 - t3) * 1e9 / (double)n : 0.;
  printf("%-16s %8.3f %8.3f %8.3f %8.0f %8.0f %7.2f%% %7.0f %8s", robust ? "embree-robust" : "embree", t1 - t0,
         t2 - t1, t2 - t1b, per_ray, per_ray, n ? 100. * (double)hits / (double)n : 0.,
         m.nt ? (double)ru.ru_maxrss * 1024. / (double)m.nt : 0., differ);
  if (shadows)
    printf(" %8.0f %7.2f%% %8s\n", ns ? (t6 - t5) * 1e9 / (double)(ns * rounds) : 0.,
           ns ? 100. * (double)blocked / (double)ns : 0., sdiffer);
  else
    printf(" %8s %8s %8s\n", "-", "-", "-");

  FILE *f = fopen(mask_path, "wb");
  if (!f || fwrite(mask, 1, n, f) != n || fclose(f)) die(mask_path, "cannot write");
  if (shadows) {
    FILE *sf = fopen(shadow_mask, "wb");
    if (!sf || fwrite(smask, 1, ns, sf) != ns || fclose(sf)) die(shadow_mask, "cannot write");
    free(smask);
  }
  rtcReleaseScene(scene);
  rtcReleaseDevice(dev);
  free(r);
  free(mask);
  return 0;
}
