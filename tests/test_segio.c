/* Tests of corise/segio: .seg parsing (accepted variants, every error with its line number),
 * file round trip, and the face-count check. */
#include "testutil.h"

#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "corise/segio.h"

static acd_status parse(const char *s, size_t expected, int **lab, size_t *n, acd_error *err) {
    return acd_seg_parse(s, strlen(s), "t.seg", expected, lab, n, err);
}

static void test_parse_ok(void **state) {
    (void)state;
    int *lab = NULL;
    size_t n = 0;
    acd_error err;
    assert_int_equal(parse("0\n1\n1\n2\n", 4, &lab, &n, &err), ACD_OK);
    assert_int_equal(n, 4);
    assert_int_equal(lab[0], 0);
    assert_int_equal(lab[3], 2);
    free(lab);
    /* CRLF, blanks around values, blank lines, signs, no final newline */
    assert_int_equal(parse("  7 \r\n\r\n\t-3\n+12\n\n2147483647\n-2147483648", ACD_SEG_ANY_COUNT, &lab, &n, &err),
                     ACD_OK);
    assert_int_equal(n, 5);
    int want[] = {7, -3, 12, INT_MAX, INT_MIN};
    assert_memory_equal(lab, want, sizeof want);
    free(lab);
    /* empty file: zero labels */
    assert_int_equal(parse("", ACD_SEG_ANY_COUNT, &lab, &n, &err), ACD_OK);
    assert_int_equal(n, 0);
    assert_null(lab);
}

static void expect_error(const char *text, size_t expected, acd_status st, const char *needle) {
    int *lab = (int *)1;
    size_t n = 99;
    acd_error err;
    assert_int_equal(acd_seg_parse(text, strlen(text), "t.seg", expected, &lab, &n, &err), st);
    assert_null(lab);
    assert_int_equal(n, 0);
    if (!strstr(err.message, needle)) {
        print_message("message '%s' lacks '%s'\n", err.message, needle);
        fail();
    }
}

static void test_parse_errors(void **state) {
    (void)state;
    expect_error("0\n1\n1.5\n", ACD_SEG_ANY_COUNT, ACD_ERR_PARSE, "t.seg:3: '1.5' is not an integer label");
    expect_error("0\nabc\n", ACD_SEG_ANY_COUNT, ACD_ERR_PARSE, "t.seg:2:");
    expect_error("0\n\n\n1 2\n", ACD_SEG_ANY_COUNT, ACD_ERR_PARSE, "t.seg:4: '1 2' holds more than one value");
    expect_error("-\n", ACD_SEG_ANY_COUNT, ACD_ERR_PARSE, "t.seg:1:");
    expect_error("1\n2147483648\n", ACD_SEG_ANY_COUNT, ACD_ERR_PARSE, "t.seg:2: label '2147483648' is outside");
    expect_error("99999999999999999999999\n", ACD_SEG_ANY_COUNT, ACD_ERR_PARSE, "outside the range");
    expect_error("0x1\n", ACD_SEG_ANY_COUNT, ACD_ERR_PARSE, "t.seg:1:");
    expect_error("0\n1\n2\n", 4, ACD_ERR_INVALID_INPUT, "t.seg: 3 labels, but the mesh has 4 faces");
    expect_error("0\n1\n2\n3\n4\n", 4, ACD_ERR_INVALID_INPUT, "5 labels, but the mesh has 4 faces");
    /* NUL byte inside */
    const char bin[] = {'1', '\n', '2', '\0', '\n'};
    int *lab = NULL;
    size_t n = 0;
    acd_error err;
    assert_int_equal(acd_seg_parse(bin, sizeof bin, "b.seg", ACD_SEG_ANY_COUNT, &lab, &n, &err), ACD_ERR_PARSE);
    assert_non_null(strstr(err.message, "b.seg:2:"));
    assert_int_equal(acd_seg_parse(NULL, 0, NULL, 0, &lab, &n, &err), ACD_OK); /* empty, 0 expected */
    assert_int_equal(acd_seg_parse("1", 1, NULL, 0, NULL, &n, &err), ACD_ERR_INVALID_ARGUMENT);
}

static void test_file_round_trip(void **state) {
    (void)state;
    char path[] = "/tmp/acd_test_segio_XXXXXX";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    close(fd);
    int labels[1000];
    for (int i = 0; i < 1000; i++) labels[i] = (i * 7919) % 13 - 6;
    acd_error err;
    assert_int_equal(acd_seg_write(path, labels, 1000, &err), ACD_OK);
    int *back = NULL;
    size_t n = 0;
    assert_int_equal(acd_seg_read(path, 1000, &back, &n, &err), ACD_OK);
    assert_int_equal(n, 1000);
    assert_memory_equal(back, labels, sizeof labels);
    free(back);
    assert_int_equal(acd_seg_read(path, 999, &back, &n, &err), ACD_ERR_INVALID_INPUT);
    assert_non_null(strstr(err.message, path));
    remove(path);
    assert_int_equal(acd_seg_read(path, ACD_SEG_ANY_COUNT, &back, &n, &err), ACD_ERR_IO);
    assert_non_null(strstr(err.message, "cannot open"));
    assert_int_equal(acd_seg_write("/nonexistent-dir/x.seg", labels, 3, &err), ACD_ERR_IO);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_parse_ok),
        cmocka_unit_test(test_parse_errors),
        cmocka_unit_test(test_file_round_trip),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
