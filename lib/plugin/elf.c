/*
 * A plugin file read as data before it is loaded.  dlopen maps a file's
 * segments as its headers say and runs its constructors: a file cut
 * short faults (SIGBUS) on the first page past its end, and a library
 * that is no plugin runs code of its own.  So a file is loaded only when
 * it is whole (every header, segment and section inside its size) and
 * its dynamic symbol table exports the plugin entry.  Every field is read
 * through bounds checked against the file's size, in the file's own
 * class and byte order, so a 32-bit or big-endian file is told for what
 * it is rather than misread.
 */
#include <dlfcn.h>
#include <elf.h>
#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "plugin/plugin-internal.h"
#include "reflect/plugin.h"

/* What the dynamic symbol table may hold at most: far more than any
 * plugin, and it bounds what a forged header can make us read. */
#define SYMBOLS_MAX (1u << 22)
#define TABLE_BYTES_MAX ((uint64_t)64 << 20)

struct elf {
	int fd;
	uint64_t size; /* of the file */
	int is64, big;
	uint64_t need; /* the end of the last thing the headers place */
	uint16_t type, machine;
	uint64_t phoff, shoff;
	uint32_t phnum, shnum, phentsize, shentsize;
};

/* Reads n bytes at off: 0, or -1 past the end of the file. */
static int
at(const struct elf *e, uint64_t off, void *buf, size_t n)
{
	ssize_t got;

	if (off > e->size || n > e->size - off)
		return -1;
	got = pread(e->fd, buf, n, (off_t)off);
	return got == (ssize_t)n ? 0 : -1;
}

static uint64_t
field(const struct elf *e, const unsigned char *p, size_t n)
{
	uint64_t v = 0;
	size_t i;

	for (i = 0; i < n; i++)
		v |= (uint64_t)p[e->big ? n - 1 - i : i] << (8 * i);
	return v;
}

/* A word of the file's class: 4 bytes in a 32-bit file, 8 in a 64-bit. */
static uint64_t
word(const struct elf *e, const unsigned char *p)
{
	return field(e, p, e->is64 ? 8 : 4);
}

/* Records that the headers place n bytes at off. */
static void
needs(struct elf *e, uint64_t off, uint64_t n)
{
	uint64_t end = off + n < off ? UINT64_MAX : off + n;

	if (end > e->need)
		e->need = end;
}

struct section {
	uint32_t type, link;
	uint64_t offset, size, entsize;
};

static int
section(const struct elf *e, uint32_t i, struct section *s)
{
	unsigned char b[64];

	if (at(e, e->shoff + (uint64_t)i * e->shentsize, b, e->is64 ? 64 : 40) < 0)
		return -1;
	s->type = (uint32_t)field(e, b + 4, 4);
	s->link = (uint32_t)field(e, b + (e->is64 ? 40 : 24), 4);
	s->offset = word(e, b + (e->is64 ? 24 : 16));
	s->size = word(e, b + (e->is64 ? 32 : 20));
	s->entsize = word(e, b + (e->is64 ? 56 : 36));
	return 0;
}

struct segment {
	uint32_t type;
	uint64_t offset, vaddr, filesz;
};

static int
segment(const struct elf *e, uint32_t i, struct segment *s)
{
	unsigned char b[56];

	if (at(e, e->phoff + (uint64_t)i * e->phentsize, b, e->is64 ? 56 : 32) < 0)
		return -1;
	s->type = (uint32_t)field(e, b, 4);
	s->offset = word(e, b + (e->is64 ? 8 : 4));
	s->vaddr = word(e, b + (e->is64 ? 16 : 8));
	s->filesz = word(e, b + (e->is64 ? 32 : 16));
	return 0;
}

/* The file offset of a virtual address, through the loaded segments. */
static int
file_offset(const struct elf *e, uint64_t vaddr, uint64_t *off)
{
	struct segment s;
	uint32_t i;

	for (i = 0; i < e->phnum; i++)
		if (segment(e, i, &s) == 0 && s.type == PT_LOAD && vaddr >= s.vaddr &&
		    vaddr - s.vaddr < s.filesz) {
			*off = s.offset + (vaddr - s.vaddr);
			return 0;
		}
	return -1;
}

/* Where the dynamic symbols and their names lie. */
struct symtab {
	uint64_t sym, nsym, syment, str, strsz;
};

/* The number of symbols a GNU hash table covers: past the highest
 * bucket's chain, which ends at an entry with its low bit set. */
static int
gnu_hash_count(const struct elf *e, uint64_t off, uint64_t *count)
{
	unsigned char b[16];
	uint32_t nbuckets, symoffset, bloom, i, max = 0;
	uint64_t buckets, chain;

	if (at(e, off, b, 16) < 0)
		return -1;
	nbuckets = (uint32_t)field(e, b, 4);
	symoffset = (uint32_t)field(e, b + 4, 4);
	bloom = (uint32_t)field(e, b + 8, 4);
	if (nbuckets > SYMBOLS_MAX || bloom > SYMBOLS_MAX)
		return -1;
	buckets = off + 16 + (uint64_t)bloom * (e->is64 ? 8 : 4);
	for (i = 0; i < nbuckets; i++) {
		if (at(e, buckets + 4 * (uint64_t)i, b, 4) < 0)
			return -1;
		if ((uint32_t)field(e, b, 4) > max)
			max = (uint32_t)field(e, b, 4);
	}
	if (max < symoffset) {
		*count = symoffset;
		return 0;
	}
	chain = buckets + 4 * (uint64_t)nbuckets;
	for (;;) {
		if (max - symoffset > SYMBOLS_MAX ||
		    at(e, chain + 4 * (uint64_t)(max - symoffset), b, 4) < 0)
			return -1;
		if (field(e, b, 4) & 1)
			break;
		max++;
	}
	*count = (uint64_t)max + 1;
	return 0;
}

/* The dynamic symbols from the dynamic section, for a file without
 * section headers (strip can leave one so). */
static int
dynamic_symtab(const struct elf *e, struct symtab *t)
{
	uint64_t symtab = 0, strtab = 0, hash = 0, gnu_hash = 0, k;
	struct segment s;
	uint32_t i;
	int found = 0;

	t->strsz = 0;
	t->syment = e->is64 ? 24 : 16;
	for (i = 0; i < e->phnum && !found; i++)
		found = segment(e, i, &s) == 0 && s.type == PT_DYNAMIC;
	if (!found)
		return -1;
	for (k = 0; k < s.filesz / (e->is64 ? 16 : 8); k++) {
		unsigned char b[16];
		uint64_t tag, val;

		if (at(e, s.offset + k * (e->is64 ? 16 : 8), b, e->is64 ? 16 : 8) < 0)
			return -1;
		tag = word(e, b);
		val = word(e, b + (e->is64 ? 8 : 4));
		if (tag == DT_NULL)
			break;
		if (tag == DT_SYMTAB)
			symtab = val;
		else if (tag == DT_STRTAB)
			strtab = val;
		else if (tag == DT_STRSZ)
			t->strsz = val;
		else if (tag == DT_SYMENT)
			t->syment = val;
		else if (tag == DT_HASH)
			hash = val;
		else if (tag == DT_GNU_HASH)
			gnu_hash = val;
	}
	if (!symtab || !strtab || file_offset(e, symtab, &t->sym) < 0 ||
	    file_offset(e, strtab, &t->str) < 0)
		return -1;
	if (hash) {
		unsigned char b[8];
		uint64_t off;

		if (file_offset(e, hash, &off) < 0 || at(e, off, b, 8) < 0)
			return -1;
		t->nsym = field(e, b + 4, 4); /* nchain: one a symbol */
	} else if (gnu_hash) {
		uint64_t off;

		if (file_offset(e, gnu_hash, &off) < 0 || gnu_hash_count(e, off, &t->nsym) < 0)
			return -1;
	} else {
		return -1;
	}
	return 0;
}

/* Whether the dynamic symbol table defines and exports name. */
static int
exports(const struct elf *e, const struct symtab *t, const char *name)
{
	size_t len = strlen(name) + 1;
	char got[64];
	uint64_t i;

	if (t->syment < (uint64_t)(e->is64 ? 24 : 16) || t->nsym > SYMBOLS_MAX ||
	    len > sizeof(got))
		return 0;
	for (i = 1; i < t->nsym; i++) {
		unsigned char b[24];
		uint64_t nameoff;
		unsigned info, other, shndx;

		if (at(e, t->sym + i * t->syment, b, e->is64 ? 24 : 16) < 0)
			return 0;
		nameoff = field(e, b, 4);
		info = e->is64 ? b[4] : b[12];
		other = e->is64 ? b[5] : b[13];
		shndx = (unsigned)field(e, b + (e->is64 ? 6 : 14), 2);
		if (shndx == SHN_UNDEF || ELF64_ST_VISIBILITY(other) == STV_HIDDEN ||
		    ELF64_ST_VISIBILITY(other) == STV_INTERNAL ||
		    (ELF64_ST_BIND(info) != STB_GLOBAL && ELF64_ST_BIND(info) != STB_WEAK))
			continue;
		if (t->strsz && (nameoff >= t->strsz || len > t->strsz - nameoff))
			continue;
		if (at(e, t->str + nameoff, got, len) == 0 && !memcmp(got, name, len))
			return 1;
	}
	return 0;
}

/* This library's own ELF identity, read from its image in memory: what
 * a plugin must match to load here. */
static int
own_identity(unsigned char *cls, unsigned char *data, uint16_t *machine)
{
	const unsigned char *self;
	Dl_info info;

	if (!dladdr((void *)rf_plugin_kind_name, &info) || !info.dli_fbase)
		return -1;
	self = info.dli_fbase;
	if (memcmp(self, ELFMAG, SELFMAG))
		return -1;
	*cls = self[EI_CLASS];
	*data = self[EI_DATA];
	memcpy(machine, self + 18, 2); /* e_machine, in our own byte order */
	return 0;
}

static const char *
class_name(int is64, int big)
{
	return is64 ? (big ? "64-bit big-endian" : "64-bit little-endian")
	            : (big ? "32-bit big-endian" : "32-bit little-endian");
}

/* The headers read, every place they give checked against the size. */
static int
read_headers(struct elf *e, const unsigned char *id, char *why, size_t len)
{
	unsigned char h[64];
	struct section s;
	struct segment g;
	uint32_t i;

	if (id[EI_CLASS] != ELFCLASS32 && id[EI_CLASS] != ELFCLASS64) {
		rf__format(why, len, "an ELF file of unknown class %u", id[EI_CLASS]);
		return RF__ELF_BROKEN;
	}
	if (id[EI_DATA] != ELFDATA2LSB && id[EI_DATA] != ELFDATA2MSB) {
		rf__format(why, len, "an ELF file of unknown byte order %u", id[EI_DATA]);
		return RF__ELF_BROKEN;
	}
	e->is64 = id[EI_CLASS] == ELFCLASS64;
	e->big = id[EI_DATA] == ELFDATA2MSB;
	needs(e, 0, e->is64 ? 64 : 52);
	if (e->need > e->size)
		goto cut;
	if (at(e, 0, h, e->is64 ? 64 : 52) < 0)
		goto unreadable;
	e->type = (uint16_t)field(e, h + 16, 2);
	e->machine = (uint16_t)field(e, h + 18, 2);
	e->phoff = word(e, h + (e->is64 ? 32 : 28));
	e->shoff = word(e, h + (e->is64 ? 40 : 32));
	e->phentsize = (uint32_t)field(e, h + (e->is64 ? 54 : 42), 2);
	e->phnum = (uint32_t)field(e, h + (e->is64 ? 56 : 44), 2);
	e->shentsize = (uint32_t)field(e, h + (e->is64 ? 58 : 46), 2);
	e->shnum = (uint32_t)field(e, h + (e->is64 ? 60 : 48), 2);
	if (e->type != ET_DYN) {
		rf__format(why, len, "an ELF file of type %u, not a shared object", e->type);
		return RF__ELF_NOT_PLUGIN;
	}
	if ((e->phnum && e->phentsize < (e->is64 ? 56u : 32u)) ||
	    ((e->shnum || e->shoff) && e->shentsize < (e->is64 ? 64u : 40u))) {
		rf__format(why, len, "its ELF header gives entries of %u and %u bytes, too "
		           "small for their kind", e->phentsize, e->shentsize);
		return RF__ELF_BROKEN;
	}
	needs(e, e->phoff, (uint64_t)e->phnum * e->phentsize);
	if (e->shoff) {
		needs(e, e->shoff, e->shentsize);
		if (e->need > e->size)
			goto cut;
		/* past 0xff00 sections, the count is section 0's size */
		if (!e->shnum) {
			if (section(e, 0, &s) < 0)
				goto unreadable;
			if (s.size > SYMBOLS_MAX) {
				rf__format(why, len, "its section 0 gives %llu sections",
				           (unsigned long long)s.size);
				return RF__ELF_BROKEN;
			}
			e->shnum = (uint32_t)s.size;
		}
		needs(e, e->shoff, (uint64_t)e->shnum * e->shentsize);
	}
	if (e->need > e->size)
		goto cut;
	for (i = 0; i < e->phnum; i++) {
		if (segment(e, i, &g) < 0)
			goto unreadable;
		if (g.type == PT_LOAD || g.type == PT_DYNAMIC)
			needs(e, g.offset, g.filesz);
	}
	for (i = 0; i < e->shnum; i++) {
		if (section(e, i, &s) < 0)
			goto unreadable;
		if (s.type != SHT_NOBITS && s.type != SHT_NULL)
			needs(e, s.offset, s.size);
	}
	if (e->need > e->size)
		goto cut;
	return 0;
cut:
	rf__format(why, len, "not a whole shared object: %llu bytes, its headers need "
	           "%llu (truncated when it was copied or built?)",
	           (unsigned long long)e->size, (unsigned long long)e->need);
	return RF__ELF_BROKEN;
unreadable:
	rf__format(why, len, "cannot read its ELF headers: %s", strerror(errno ? errno : EIO));
	return RF__ELF_BROKEN;
}

int
rf__elf_check(const char *path, char *why, size_t len)
{
	unsigned char id[EI_NIDENT], cls, data;
	struct elf e;
	struct symtab t;
	struct section s, str;
	struct stat st;
	uint16_t machine;
	uint32_t i;
	int rc, have = 0;

	memset(&e, 0, sizeof(e));
	if ((e.fd = open(path, O_RDONLY | O_CLOEXEC)) < 0) {
		rf__format(why, len, "cannot open it: %s", strerror(errno));
		return RF__ELF_BROKEN;
	}
	if (fstat(e.fd, &st) < 0) {
		rf__format(why, len, "cannot open it: %s", strerror(errno));
		rc = RF__ELF_BROKEN;
		goto out;
	}
	e.size = (uint64_t)st.st_size;
	errno = 0;
	if (at(&e, 0, id, sizeof(id)) < 0 || memcmp(id, ELFMAG, SELFMAG)) {
		rf__format(why, len, "not a shared object (no ELF header)");
		rc = RF__ELF_NOT_PLUGIN;
		goto out;
	}
	if ((rc = read_headers(&e, id, why, len)) != 0)
		goto out;
	for (i = 0; i < e.shnum && !have; i++)
		if (section(&e, i, &s) == 0 && s.type == SHT_DYNSYM && s.link < e.shnum &&
		    section(&e, s.link, &str) == 0 && s.entsize) {
			t.sym = s.offset;
			t.syment = s.entsize;
			t.nsym = s.size / s.entsize;
			t.str = str.offset;
			t.strsz = str.size;
			have = 1;
		}
	if (!have && dynamic_symtab(&e, &t) < 0) {
		rf__format(why, len, "a shared object without dynamic symbols");
		rc = RF__ELF_NOT_PLUGIN;
		goto out;
	}
	if (t.nsym > SYMBOLS_MAX || t.strsz > TABLE_BYTES_MAX ||
	    !exports(&e, &t, RF_PLUGIN_ENTRY)) {
		rf__format(why, len, "not a reflect plugin, it exports no %s(); define "
		           "it with RF_PLUGIN_DEFINE(descriptor) from <reflect/plugin.h>, "
		           "or remove the file from the plugin path", RF_PLUGIN_ENTRY);
		rc = RF__ELF_NOT_PLUGIN;
		goto out;
	}
	if (own_identity(&cls, &data, &machine) == 0 &&
	    (cls != id[EI_CLASS] || data != id[EI_DATA] || machine != e.machine)) {
		rf__format(why, len, "built for another machine (ELF machine %u, %s), this "
		           "reflect runs on ELF machine %u, %s; rebuild it here", e.machine,
		           class_name(e.is64, e.big), machine,
		           class_name(cls == ELFCLASS64, data == ELFDATA2MSB));
		rc = RF__ELF_BROKEN;
		goto out;
	}
	rc = 0;
out:
	close(e.fd);
	return rc;
}
