/* The word a misspelt one most likely meant, for "did you mean" in
 * messages. */
#include <string.h>

#include "util/util.h"

/* Optimal string alignment distance (insertions, deletions, changes and
 * swaps of two neighbours each cost 1), or cap + 1 once it exceeds cap:
 * names are short, and a long one is never close. */
static size_t
distance(const char *a, const char *b, size_t cap)
{
	size_t la = strlen(a), lb = strlen(b), i, j;
	size_t d[3][65], *prev2 = d[0], *prev = d[1], *cur = d[2], *t;

	if (la > 64 || lb > 64)
		return cap + 1;
	if ((la > lb ? la - lb : lb - la) > cap)
		return cap + 1;
	for (j = 0; j <= lb; j++)
		prev[j] = j;
	for (i = 1; i <= la; i++) {
		size_t best = cur[0] = i;

		for (j = 1; j <= lb; j++) {
			size_t v = prev[j - 1] + (a[i - 1] != b[j - 1]);

			if (prev[j] + 1 < v)
				v = prev[j] + 1;
			if (cur[j - 1] + 1 < v)
				v = cur[j - 1] + 1;
			if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] &&
			    prev2[j - 2] + 1 < v)
				v = prev2[j - 2] + 1;
			cur[j] = v;
			if (v < best)
				best = v;
		}
		if (best > cap)
			return cap + 1;
		t = prev2;
		prev2 = prev;
		prev = cur;
		cur = t;
	}
	return prev[lb];
}

int
rf__closest(const char *word, const char *const *names, size_t n)
{
	/* a third of the word, at least 1 and at most 3 edits: "aprox" is
	 * approx, "box" is not "bevel" */
	size_t len = strlen(word), cap = len / 3, best = (size_t)-1, i, d;
	int found = -1;

	if (cap < 1)
		cap = 1;
	if (cap > 3)
		cap = 3;
	for (i = 0; i < n; i++) {
		if (!names[i] || !strcmp(names[i], word))
			continue;
		d = distance(word, names[i], cap);
		if (d <= cap && d < best && d < strlen(names[i])) {
			best = d;
			found = (int)i;
		}
	}
	return found;
}
