/* Tests of Lucent's own mesh readers (issue 17): the PLY reader and its property API (ASCII, binary
 * little and big endian, .ply.gz), the OBJ reader, and what they do with hostile input: every count,
 * index and offset checked, truncation named by line or byte, only regular files read, no file but the
 * named one opened. The expected values are the ones written into each file here. */
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include "lucent/mesh.h"
#include "test.h"

static const char *bad(const char *name)
{
    static char buf[2][1024];
    static int k;
    k ^= 1;
    snprintf(buf[k], sizeof buf[k], "%s/tests/fixtures/bad-meshes/%s", LUCENT_SOURCE_DIR, name);
    return buf[k];
}

static void put_file(const char *path, const void *data, size_t n)
{
    FILE *f = fopen(path, "wb");
    if (f) fwrite(data, 1, n, f), fclose(f);
}

/* Three vertices with x y z, an unused int, nx, and colours; one quad face. */
static const char k_ascii[] = "ply\r\nformat ascii 1.0\ncomment made by hand\nelement vertex 4\n"
                              "property float x\nproperty float y\nproperty float z\nproperty int flags\n"
                              "property double nx\nproperty uchar red\nelement face 1\n"
                              "property list uchar int vertex_indices\nelement extra 2\nproperty list int float q\n"
                              "end_header\n"
                              "0 0 0 7 0.5 255\n1 0 0 7 0.25 128 \n\n1 1 0 7 -1e-3 0\n0 1 0 7 1.5e2 1\n4 0 1 2 3\n"
                              "2 1.5 2.5\n0\n";

/* The same content in binary, little or big endian. */
static size_t binary_ply(int big, unsigned char *dest)
{
    const char *hdr = big ? "binary_big_endian" : "binary_little_endian";
    int n = sprintf((char *)dest,
                    "ply\nformat %s 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
                    "property int flags\nproperty double nx\nproperty uchar red\nelement face 1\n"
                    "property list uchar int vertex_indices\nelement extra 2\nproperty list int float q\nend_header\n",
                    hdr);
    unsigned char *p = dest + n;
    float xyz[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    double nx[4] = {0.5, 0.25, -1e-3, 150};
    unsigned char red[4] = {255, 128, 0, 1};
    for (int v = 0; v < 4; v++) {
        unsigned char b[8];
        for (int k = 0; k < 3; k++) {
            memcpy(b, &xyz[v][k], 4);
            for (int i = 0; i < 4; i++) *p++ = b[big ? 3 - i : i];
        }
        int32_t flags = 7;
        memcpy(b, &flags, 4);
        for (int i = 0; i < 4; i++) *p++ = b[big ? 3 - i : i];
        memcpy(b, &nx[v], 8);
        for (int i = 0; i < 8; i++) *p++ = b[big ? 7 - i : i];
        *p++ = red[v];
    }
    *p++ = 4;
    for (int32_t i = 0; i < 4; i++)
        for (int k = 0; k < 4; k++) *p++ = (unsigned char)(i >> (8 * (big ? 3 - k : k)));
    /* extra: a list of 2 floats (1.5, 2.5), then an empty list. */
    int32_t two = 2, zero = 0;
    float q[2] = {1.5f, 2.5f};
    unsigned char b[4];
    memcpy(b, &two, 4);
    for (int i = 0; i < 4; i++) *p++ = b[big ? 3 - i : i];
    for (int j = 0; j < 2; j++) {
        memcpy(b, &q[j], 4);
        for (int i = 0; i < 4; i++) *p++ = b[big ? 3 - i : i];
    }
    memcpy(b, &zero, 4);
    for (int i = 0; i < 4; i++) *p++ = b[big ? 3 - i : i];
    return (size_t)(p - dest);
}

static void check_content(lucent_ply *ply, const char *what)
{
    CHECK(lucent_ply_vertex_count(ply) == 4 && lucent_ply_face_count(ply) == 1);
    CHECK(lucent_ply_property_count(ply) == 6);
    CHECK(lucent_ply_property_index(ply, "nx") == 4 && lucent_ply_property_index(ply, "blue") == -1);
    CHECK(strcmp(lucent_ply_property_name(ply, 5), "red") == 0);
    const char *names[] = {"red", "x", "y", "nx", "blue"};
    lucent_ply_data d;
    CHECK_OK(lucent_ply_read(
        ply,
        &(lucent_ply_read_desc){.names = names, .count = 5, .allow_missing = 1, .faces = LUCENT_PLY_FACES_OPTIONAL},
        &d));
    if (!d.values) return;
    printf("  %s: %zu vertices, %zu triangles\n", what, d.vertex_count, d.triangle_count);
    CHECK(d.vertex_count == 4 && d.count == 5 && d.triangle_count == 2 && d.polygon_count == 1);
    double want[4][4] = {{255, 0, 0, 0.5}, {128, 1, 0, 0.25}, {0, 1, 1, -1e-3}, {1, 0, 1, 150}};
    for (int v = 0; v < 4; v++) {
        for (int k = 0; k < 4; k++) CHECK(d.values[5 * v + k] == want[v][k]);
        CHECK(isnan(d.values[5 * v + 4]));
    }
    /* The quad 0 1 2 3 as the fan (0 1 2) (0 2 3). */
    uint32_t tri[6] = {0, 1, 2, 0, 2, 3};
    for (int i = 0; i < 6; i++) CHECK(d.triangles[i] == tri[i]);
    lucent_ply_data_free(&d);
}

/* ASCII, binary LE and BE, and gzip give the same values through the property API. */
TEST(ply_property_api_all_encodings)
{
    lucent_ply *ply;
    CHECK_OK(lucent_ply_open_memory(k_ascii, sizeof k_ascii - 1, "a.ply", &ply));
    if (ply) check_content(ply, "ascii"), lucent_ply_close(ply);
    unsigned char bin[2048];
    for (int big = 0; big < 2; big++) {
        size_t n = binary_ply(big, bin);
        CHECK_OK(lucent_ply_open_memory(bin, n, "b.ply", &ply));
        if (ply) check_content(ply, big ? "big endian" : "little endian"), lucent_ply_close(ply);
        /* Gzipped, from a file. */
        gzFile gz = gzopen(test_path("b.ply.gz"), "wb");
        gzwrite(gz, bin, (unsigned)n);
        gzclose(gz);
        CHECK_OK(lucent_ply_open(test_path("b.ply.gz"), &ply));
        if (ply) check_content(ply, "gzip"), lucent_ply_close(ply);
    }
    /* Floats as float: ASCII 0.1 read into a float property is the float nearest 0.1, as binary stores it. */
    static const char tenth[] = "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty double y\n"
                                "end_header\n0.1 0.1\n";
    CHECK_OK(lucent_ply_open_memory(tenth, sizeof tenth - 1, "t.ply", &ply));
    const char *xy[] = {"x", "y"};
    lucent_ply_data d = {0};
    if (ply) CHECK_OK(lucent_ply_read(ply, &(lucent_ply_read_desc){.names = xy, .count = 2, .single = 0}, &d));
    if (d.values) CHECK(d.values[0] == (double)0.1f && d.values[1] == 0.1);
    lucent_ply_data_free(&d);
    lucent_ply_close(ply);
    /* Single precision output. */
    CHECK_OK(lucent_ply_open_memory(tenth, sizeof tenth - 1, "t.ply", &ply));
    if (ply) CHECK_OK(lucent_ply_read(ply, &(lucent_ply_read_desc){.names = xy, .count = 2, .single = 1}, &d));
    if (d.values32) CHECK(d.values32[0] == 0.1f && d.values32[1] == 0.1f && !d.values);
    lucent_ply_data_free(&d);
    lucent_ply_close(ply);
}

/* A PLY without faces reads as points; the mesh path says it needs faces. */
TEST(faceless_ply_points_and_mesh_error)
{
    lucent_ply *ply;
    CHECK_OK(lucent_ply_open(bad("hand-segv-ply-no-faces.ply"), &ply));
    const char *xyz[] = {"x", "y", "z"};
    lucent_ply_data d = {0};
    if (ply) CHECK_OK(lucent_ply_read(ply, &(lucent_ply_read_desc){.names = xyz, .count = 3}, &d));
    CHECK(d.vertex_count == 3 && d.triangle_count == 0);
    if (d.values) CHECK(d.values[3] == 1 && d.values[7] == 1);
    lucent_ply_data_free(&d);
    lucent_ply_close(ply);
    lucent_mesh *m = NULL;
    CHECK_ERR(lucent_mesh_load(bad("hand-segv-ply-no-faces.ply"), NULL, &m), LUCENT_ERR_PARSE,
              "hand-segv-ply-no-faces.ply", "points only");
    CHECK(!m);
    /* A property the file lacks, without allow_missing. */
    CHECK_OK(lucent_ply_open(bad("hand-segv-ply-no-faces.ply"), &ply));
    const char *op[] = {"opacity"};
    if (ply)
        CHECK_ERR(lucent_ply_read(ply, &(lucent_ply_read_desc){.names = op, .count = 1}, &d), LUCENT_ERR_PARSE,
                  "no property opacity");
    lucent_ply_close(ply);
}

/* Each bad PLY gives a parse error naming the file and the place. */
TEST(hostile_ply)
{
    static const struct {
        const char *text, *expect;
    } k[] = {
        {"ply\nformat binary_b\x01\x00\x00\x1e\x03"
         "f",
         "format"},
        {"ply\nformat ascii 1.0\nelement vertex 2000000000\nproperty float x\nproperty float y\nproperty float z\n"
         "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n",
         "declares 2000000000 vertex entries"},
        {"ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
         "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n",
         "declares 3 vertex entries"},
        {"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n", "without end_header"},
        {"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
         "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n",
         "line 13: face 0: vertex index 3 out of range"},
        {"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
         "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n",
         "line 13: face 0"},
        {"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
         "element face 2\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
         "truncated: the file ends at line 13, in face 1 of 2"},
        {"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
         "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0\n0 1 0\n3 0 1 2\n",
         "line 11: vertex 1: property z: missing value"},
        {"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
         "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0 0\n0 1 0\n3 0 1 2\n",
         "line 11: vertex 1: more values"},
        {"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
         "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 zz 0\n0 1 0\n3 0 1 2\n",
         "property y: not a number"},
        {"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
         "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n99999999 0 1 2\n",
         "bad list length"},
        {"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
         "element face 1\nproperty list uchar float vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
         "not of an integer type"},
        {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
         "element face 1\nproperty list uchar int vertex_indices\nend_header\nnan 0 0\n3 0 0 0\n",
         "not finite"},
        {"ply\nformat ascii 1.0\nelement vertex 99999999999999999999\n", "not a non-negative integer"},
        {"ply\nformat ascii 1.0\nbogus\nend_header\n", "line 3: unknown header keyword"},
        {"PLY\n", "not a PLY file"},
    };
    for (size_t i = 0; i < sizeof k / sizeof k[0]; i++) {
        lucent_mesh *m = NULL;
        char name[32];
        snprintf(name, sizeof name, "hostile%zu.ply", i);
        CHECK_ERR(
            lucent_mesh_load_memory(k[i].text, strlen(k[i].text), name, &(lucent_mesh_load_desc){.format = "ply"}, &m),
            LUCENT_ERR_PARSE, name, k[i].expect);
        CHECK(!m);
    }
    /* Binary truncation names the byte offset: the tetrahedron-like file cut inside its faces. */
    unsigned char bin[2048];
    size_t n = binary_ply(0, bin);
    lucent_ply *ply;
    CHECK_OK(lucent_ply_open_memory(bin, n - 20, "cut.ply", &ply));
    lucent_ply_data d;
    if (ply)
        CHECK_ERR(lucent_ply_read(ply, &(lucent_ply_read_desc){.faces = LUCENT_PLY_FACES_OPTIONAL}, &d),
                  LUCENT_ERR_PARSE, "cut.ply", "truncated at byte", "face 0 of 1");
    lucent_ply_close(ply);
    /* A truncated .ply.gz: zlib's end of stream is checked. */
    unsigned char gzbuf[4096];
    uLongf gzn = sizeof gzbuf;
    z_stream zs = {0};
    deflateInit2(&zs, 9, Z_DEFLATED, 16 + MAX_WBITS, 8, Z_DEFAULT_STRATEGY);
    zs.next_in = (unsigned char *)k_ascii, zs.avail_in = sizeof k_ascii - 1;
    zs.next_out = gzbuf, zs.avail_out = (unsigned)gzn;
    deflate(&zs, Z_FINISH);
    gzn = zs.total_out;
    deflateEnd(&zs);
    put_file(test_path("cut.ply.gz"), gzbuf, gzn - 12);
    lucent_mesh *m = NULL;
    CHECK_ERR(lucent_mesh_load(test_path("cut.ply.gz"), NULL, &m), LUCENT_ERR_PARSE, "cut.ply.gz", "truncated");
    put_file(test_path("whole.ply.gz"), gzbuf, gzn);
    CHECK_OK(lucent_mesh_load(test_path("whole.ply.gz"), NULL, &m));
    if (m) CHECK(m->vertex_count == 4 && m->face_count == 2);
    lucent_mesh_destroy(m);
    /* The reproducers of issue 17. */
    CHECK_ERR(lucent_mesh_load(bad("fuzz-min-segv-ply-header.ply"), NULL, &m), LUCENT_ERR_PARSE,
              "fuzz-min-segv-ply-header.ply");
}

/* Only regular files: a FIFO and a device are refused before any read (neither would end). */
TEST(fifo_and_device_refused)
{
    const char *fifo = test_path("pipe.ply");
    unlink(fifo);
    lucent_mesh *m = NULL;
    if (mkfifo(fifo, 0600) == 0) {
        CHECK_ERR(lucent_mesh_load(fifo, NULL, &m), LUCENT_ERR_IO, "pipe.ply", "FIFO");
        unlink(fifo);
    }
    CHECK_ERR(lucent_mesh_load("/dev/urandom", &(lucent_mesh_load_desc){.format = "ply"}, &m), LUCENT_ERR_IO,
              "/dev/urandom", "device");
    CHECK_ERR(lucent_mesh_load("/dev/zero", &(lucent_mesh_load_desc){.format = "obj"}, &m), LUCENT_ERR_IO, "device");
    CHECK(!m);
}

/* OBJ: the index forms, negative indices, polygons, ignored statements; mtllib opens nothing. */
TEST(obj_reader)
{
    static const char obj[] = "# a quad and a triangle\nmtllib /etc/passwd\nmtllib ../../x.mtl\no quad\n"
                              "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\nusemtl m\n"
                              "f 1/1/1 2/1/1 3//1 4\nv 2 0 0\nf -1 -4 -3\nl 1 2\np 1\n";
    lucent_mesh *m = NULL;
    CHECK_OK(lucent_mesh_load_memory(obj, sizeof obj - 1, "q.obj",
                                     &(lucent_mesh_load_desc){.format = "obj", .keep_duplicates = 1}, &m));
    if (m) {
        CHECK(m->vertex_count == 5 && m->face_count == 3);
        uint32_t want[9] = {0, 1, 2, 0, 2, 3, 4, 1, 2};
        for (int i = 0; i < 9; i++) CHECK(m->faces[i] == want[i]);
    }
    lucent_mesh_destroy(m), m = NULL;
    static const struct {
        const char *text, *expect;
    } k[] = {
        {"v 0 0 0\nv 1 0 0\nf 1 2 3\n", "line 3: face index 3 does not name a vertex (2 defined so far)"},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "line 4: face index 0"},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf -4 1 2\n", "face index -4"},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n", "line 4: a face needs 3"},
        {"v 0 0\n", "line 1: a vertex needs three finite coordinates"},
        {"v 0 0 inf\n", "line 1"},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n", "not an integer"},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999\n", "not an integer"},
        {"v 0 0 1 s ply\n", "no faces"},
    };
    for (size_t i = 0; i < sizeof k / sizeof k[0]; i++) {
        char name[32];
        snprintf(name, sizeof name, "bad%zu.obj", i);
        CHECK_ERR(
            lucent_mesh_load_memory(k[i].text, strlen(k[i].text), name, &(lucent_mesh_load_desc){.format = "obj"}, &m),
            LUCENT_ERR_PARSE, name, k[i].expect);
        CHECK(!m);
    }
    CHECK_ERR(lucent_mesh_load(bad("fuzz-uaf-obj-point.obj"), NULL, &m), LUCENT_ERR_PARSE, "fuzz-uaf-obj-point.obj");
    /* A line longer than the reader's bound. */
    size_t big = ((size_t)1 << 20) + 16;
    char *line = malloc(big + 1);
    if (line) {
        memset(line, ' ', big), line[0] = 'v', line[big] = '\0';
        CHECK_ERR(lucent_mesh_load_memory(line, big, "long.obj", &(lucent_mesh_load_desc){.format = "obj"}, &m),
                  LUCENT_ERR_PARSE, "long.obj", "line 1: longer than");
        free(line);
    }
}

/* The other formats go through assimp in a child, on a closed file system: an OFF that crashed it
 * becomes an error, and an STL reads. */
TEST(assimp_formats_in_child)
{
    static const char stl[] = "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
                              "endloop\nendfacet\nendsolid t\n";
    lucent_mesh *m = NULL;
    CHECK_OK(lucent_mesh_load_memory(stl, sizeof stl - 1, "t.stl", &(lucent_mesh_load_desc){.format = "stl"}, &m));
    if (m) CHECK(m->vertex_count == 3 && m->face_count == 1);
    lucent_mesh_destroy(m), m = NULL;
    static const char off[] = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1\n";
    lucent_status s =
        lucent_mesh_load_memory(off, sizeof off - 1, "cut.off", &(lucent_mesh_load_desc){.format = "off"}, &m);
    CHECK(s == LUCENT_ERR_PARSE && strstr(lucent_last_error(), "cut.off"));
    printf("  truncated OFF: %s\n", lucent_last_error());
    lucent_mesh_destroy(m);
}
/* Issue 32 item 6: decompression bombs. A .ply.gz whose header claims more rows than 100 times its
 * compressed size can give is refused from the header; one whose lists inflate past that is refused as it
 * inflates; the read limit (elements) holds for plain files and for OBJ too, and is set by the API. */
TEST(gzip_bombs_and_the_read_limit)
{
    lucent_mesh *m = NULL;
    CHECK_ERR(lucent_mesh_load(bad("bomb-ply-gz-mesh-30m-faces.ply.gz"), NULL, &m), LUCENT_ERR_PARSE,
              "bomb-ply-gz-mesh-30m-faces.ply.gz", "declares 30000000 face entries", "decompression bomb");
    CHECK_ERR(lucent_mesh_load(bad("hand-gz-list-bomb.ply.gz"), NULL, &m), LUCENT_ERR_PARSE,
              "hand-gz-list-bomb.ply.gz: gzip data inflating more than 100 times its size");
    static const char tetra[] = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                                "property float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n"
                                "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
    CHECK(lucent_mesh_read_limit() == LUCENT_MESH_DEFAULT_READ_ELEMENTS || getenv("LUCENT_MESH_MAX_ELEMENTS"));
    lucent_mesh_set_read_limit(7);
    CHECK_ERR(lucent_mesh_load_memory(tetra, strlen(tetra), "tetra.ply", &(lucent_mesh_load_desc){.format = "ply"}, &m),
              LUCENT_ERR_PARSE, "tetra.ply", "declares 4 face entries (8 rows in all so far)", "read limit of 7");
    static const char obj[] = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
    CHECK_ERR(lucent_mesh_load_memory(obj, strlen(obj), "tetra.obj", &(lucent_mesh_load_desc){.format = "obj"}, &m),
              LUCENT_ERR_PARSE, "tetra.obj: line 8: more than 7");
    lucent_mesh_set_read_limit(8);
    CHECK_OK(lucent_mesh_load_memory(tetra, strlen(tetra), "tetra.ply", &(lucent_mesh_load_desc){.format = "ply"}, &m));
    lucent_mesh_destroy(m), m = NULL;
    lucent_mesh_set_read_limit(0);
    CHECK(m == NULL);
}

TEST_MAIN(TEST_ENTRY(gzip_bombs_and_the_read_limit), TEST_ENTRY(ply_property_api_all_encodings),
          TEST_ENTRY(faceless_ply_points_and_mesh_error), TEST_ENTRY(hostile_ply), TEST_ENTRY(fifo_and_device_refused),
          TEST_ENTRY(obj_reader), TEST_ENTRY(assimp_formats_in_child))
