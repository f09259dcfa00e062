/* Meshes in the formats we do not parse ourselves (FBX, COLLADA, 3DS, ...), by extension only, read through
 * the C API of the Open Asset Import Library (Debian's libassimp-dev) when the build found it
 * (SS_HAVE_ASSIMP), else refused with a message naming the package.
 *
 * The scene is flattened: every node's meshes, with the node's accumulated transform applied to their
 * vertices (the scene as it is drawn; a mesh instanced by several nodes appears once per instance),
 * in depth-first node order; only triangles are kept (polygons are triangulated by assimp, points and
 * lines dropped). Vertices are then welded by exact coordinates: the formats split vertices at normal
 * creases and texture seams, which would cut the surface apart. assimp's own JoinIdenticalVertices compares normals and texture coordinates too, so it cannot
 * do this; ssi_mesh_weld does it by sorting. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mesh/io_internal.h"
#include "specseg/io.h"

/* ---- which files go to assimp -------------------------------------------------------------------- */

/* Formats we always route to assimp (and name in the message when it is missing); with assimp, any
 * extension it reports as supported also goes to it (OFF, OBJ, PLY, STL and glTF / GLB stay with our own
 * readers: assimp's glTF importer crashed on malformed input). */
static const char *const KNOWN[] = {"fbx", "dae", "3ds", "blend", "x3d", "3mf", "x", "lwo",
                                    "ase", "ms3d", "ifc", "ac", "dxf", "md2", "md3", "md5mesh", "smd", "ogex", "b3d",
                                    "cob", "q3o", "q3s", "irr", "irrmesh", "lws", "nff", "raw", "ter", "xgl", "zgl", NULL};

static int lower_ext(const char *path, char *out, size_t cap) {
  const char *dot = strrchr(path, '.'), *slash = strrchr(path, '/');
  if (!dot || (slash && dot < slash) || !dot[1]) return 0;
  size_t n = strlen(dot + 1);
  if (n + 1 > cap) return 0;
  for (size_t i = 0; i <= n; i++) {
    char c = dot[1 + i];
    out[i] = (char)(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
  }
  return 1;
}

#ifdef SS_HAVE_ASSIMP
#include <assimp/cimport.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <pthread.h>
#include <sys/stat.h>
/* aiGetErrorString is one process-wide string: imports are serialised so that each failure reads its
 * own message (and so that assimp's shared logger state is never used from two threads). */
static pthread_mutex_t assimp_lock = PTHREAD_MUTEX_INITIALIZER;
#endif

int ssi_mesh_assimp_ext(const char *path, char *hint, size_t cap) {
  char ext[16];
  if (!path || !lower_ext(path, ext, sizeof ext)) return 0;
  if (ssi_mesh_own_format(path)) return 0;
  int known = 0;
  for (const char *const *k = KNOWN; *k && !known; k++) known = !strcmp(*k, ext);
#ifdef SS_HAVE_ASSIMP
  if (!known) {
    char dotted[20];
    snprintf(dotted, sizeof dotted, ".%s", ext);
    pthread_mutex_lock(&assimp_lock);
    known = aiIsExtensionSupported(dotted) == AI_TRUE;
    pthread_mutex_unlock(&assimp_lock);
  }
#endif
  if (known && hint) snprintf(hint, cap, "%s", ext);
  return known;
}

/* "FBX", "DAE", ... for messages */
static const char *format_name(const char *hint, char *up, size_t cap) {
  size_t i = 0;
  for (; hint && hint[i] && i + 1 < cap; i++) up[i] = (char)(hint[i] >= 'a' && hint[i] <= 'z' ? hint[i] - 'a' + 'A' : hint[i]);
  up[i] = '\0';
  return i ? up : "mesh";
}

#ifndef SS_HAVE_ASSIMP

ss_status ssi_read_assimp(const char *path, const char *name, const char *buf, size_t len, const char *hint, ss_mesh *m,
                          ss_error *err) {
  (void)path, (void)buf, (void)len;
  memset(m, 0, sizeof *m);
  char up[16];
  return ss_fail(err, SS_ERR_UNSUPPORTED,
                 "%s: reading %s files needs the Open Asset Import Library: install libassimp-dev and rebuild specseg "
                 "(this build reads OFF, OBJ, PLY, STL and glTF only)",
                 name ? name : "<memory>", format_name(hint, up, sizeof up));
}

#else

typedef struct flat {
  io_dvec V;
  io_ivec F;
  long meshes, dropped; /* meshes placed, non-triangle faces dropped */
  ss_status st;
  const char *name;
  ss_error *err;
} flat;

/* row-major 4x4 product r = a b (assimp's aiMatrix4x4: a1..a4 the first row) */
static void mat_mul(const double *a, const double *b, double *r) {
  for (int i = 0; i < 4; i++)
    for (int j = 0; j < 4; j++) {
      double s = 0;
      for (int k = 0; k < 4; k++) s += a[4 * i + k] * b[4 * k + j];
      r[4 * i + j] = s;
    }
}

static void mat_from_ai(const struct aiMatrix4x4 *t, double *r) {
  const ai_real *p = &t->a1; /* a1 a2 a3 a4 b1 ... d4, row-major and contiguous */
  for (int i = 0; i < 16; i++) r[i] = (double)p[i];
}

static int add_mesh(flat *fl, const struct aiMesh *me, const double *T) {
  if (!me || !me->mVertices) return 0;
  if ((uint64_t)fl->V.n / 3 + me->mNumVertices > IO_MAX_ELEMENTS) {
    fl->st = ss_fail(fl->err, SS_ERR_INVALID, "%s: more than %d vertices", fl->name, IO_MAX_ELEMENTS);
    return -1;
  }
  const int base = (int)(fl->V.n / 3);
  for (unsigned v = 0; v < me->mNumVertices; v++) {
    double x = me->mVertices[v].x, y = me->mVertices[v].y, z = me->mVertices[v].z;
    double p[3];
    for (int r = 0; r < 3; r++) p[r] = T[4 * r] * x + T[4 * r + 1] * y + T[4 * r + 2] * z + T[4 * r + 3];
    double w = T[12] * x + T[13] * y + T[14] * z + T[15];
    if (w != 1.0 && w != 0.0)
      for (int r = 0; r < 3; r++) p[r] /= w;
    for (int r = 0; r < 3; r++)
      if (io_dvec_push(&fl->V, p[r])) goto nomem;
  }
  for (unsigned f = 0; f < me->mNumFaces; f++) {
    const struct aiFace *fa = &me->mFaces[f];
    if (fa->mNumIndices != 3 || !fa->mIndices) {
      fl->dropped++;
      continue;
    }
    for (int c = 0; c < 3; c++)
      if (fa->mIndices[c] >= me->mNumVertices) {
        fl->st = ss_fail(fl->err, SS_ERR_PARSE, "%s: mesh '%s': face %u: vertex %u out of range (%u vertices)", fl->name,
                         me->mName.data, f, fa->mIndices[c], me->mNumVertices);
        return -1;
      }
    if (fl->F.n / 3 >= IO_MAX_ELEMENTS) {
      fl->st = ss_fail(fl->err, SS_ERR_INVALID, "%s: more than %d faces", fl->name, IO_MAX_ELEMENTS);
      return -1;
    }
    for (int c = 0; c < 3; c++)
      if (io_ivec_push(&fl->F, base + (int)fa->mIndices[c])) goto nomem;
  }
  fl->meshes++;
  return 0;
nomem:
  fl->st = ss_fail(fl->err, SS_ERR_NOMEM, "%s: out of memory", fl->name);
  return -1;
}

static int add_node(flat *fl, const struct aiScene *sc, const struct aiNode *nd, const double *parent, int depth) {
  if (!nd) return 0;
  if (depth > 1000) {
    fl->st = ss_fail(fl->err, SS_ERR_PARSE, "%s: scene graph deeper than 1000 nodes", fl->name);
    return -1;
  }
  double local[16], T[16];
  mat_from_ai(&nd->mTransformation, local);
  mat_mul(parent, local, T);
  for (unsigned i = 0; i < nd->mNumMeshes; i++) {
    unsigned mi = nd->mMeshes[i];
    if (mi >= sc->mNumMeshes) {
      fl->st = ss_fail(fl->err, SS_ERR_PARSE, "%s: node '%s' refers to mesh %u of %u", fl->name, nd->mName.data, mi,
                       sc->mNumMeshes);
      return -1;
    }
    if (add_mesh(fl, sc->mMeshes[mi], T)) return -1;
  }
  for (unsigned c = 0; c < nd->mNumChildren; c++)
    if (add_node(fl, sc, nd->mChildren[c], T, depth + 1)) return -1;
  return 0;
}

ss_status ssi_read_assimp(const char *path, const char *name, const char *buf, size_t len, const char *hint, ss_mesh *m,
                          ss_error *err) {
  memset(m, 0, sizeof *m);
  if (!name) name = path ? path : "<memory>";
  /* polygons triangulated; no other processing (JoinIdenticalVertices is not exact: see the top) */
  const unsigned flags = aiProcess_Triangulate;
  pthread_mutex_lock(&assimp_lock);
  const struct aiScene *sc;
  if (path) sc = aiImportFile(path, flags); /* by path: files a scene refers to are found beside it */
  else if (len > (size_t)UINT32_MAX) sc = NULL;
  else sc = aiImportFileFromMemory(buf, (unsigned)len, flags, hint ? hint : "");
  if (!sc) {
    const char *why = len > (size_t)UINT32_MAX && !path ? "larger than 4 GB" : aiGetErrorString();
    char up[16];
    ss_status st = ss_fail(err, SS_ERR_PARSE, "%s: %s (assimp): %s", name, format_name(hint, up, sizeof up),
                           why && *why ? why : "import failed");
    pthread_mutex_unlock(&assimp_lock);
    return st;
  }
  pthread_mutex_unlock(&assimp_lock);
  flat fl;
  memset(&fl, 0, sizeof fl);
  fl.name = name, fl.err = err;
  static const double I[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  int bad = add_node(&fl, sc, sc->mRootNode, I, 0);
  unsigned nmeshes = sc->mNumMeshes;
  aiReleaseImport(sc); /* thread-safe: frees this scene only */
  ss_status st = bad ? fl.st : SS_OK;
  if (!st && fl.F.n == 0)
    st = ss_fail(err, SS_ERR_PARSE, "%s: no triangles in the scene (%u meshes, %ld faces that are points or lines)", name,
                 nmeshes, fl.dropped);
  if (!st) st = io_finish_mesh(&fl.V, &fl.F, m, name, err);
  if (!st) st = ssi_mesh_weld(m, NULL, err);
  free(fl.V.a), free(fl.F.a);
  if (st) ss_mesh_free(m);
  return st;
}

#endif
