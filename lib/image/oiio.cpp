// The bridge from OpenImageIO (C++) to libreflect's C image API, built as
// a module that libreflect loads on first use (see image.c).
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <memory>
#include <new>
#include <string>
#include <system_error>
#include <vector>

extern "C" {
#include "image/module.h"
}

using namespace OIIO;

struct rf_image {
	size_t width, height, nchannels;
	std::vector<float> pixels;
	std::vector<std::string> names;
	std::vector<std::pair<std::string, std::string>> attributes;
};

// The file an image is written to: OpenImageIO's stdio proxy, remembering
// the first failed write (some format writers do not check theirs), so a
// full disk is an error and not a silently short file.
class checked_file : public Filesystem::IOFile {
public:
	explicit checked_file(FILE *fp) : IOFile(fp, Write), fp_(fp) {}
	// Not "file": a writer that sees a "file" proxy may take its FILE
	// and write to it directly, past the checks below.
	const char *proxytype() const override { return "reflect-checked-file"; }
	// After a failure, writes are skipped and reported as done: some
	// format libraries (libjpeg) end the process on a short write, and
	// the error is reported when the image is closed.
	size_t write(const void *buf, size_t size) override
	{
		if (error_) {
			m_pos += (int64_t)size;
			return size;
		}
		return note(IOFile::write(buf, size), size);
	}
	size_t pwrite(const void *buf, size_t size, int64_t offset) override
	{
		if (error_)
			return size;
		return note(IOFile::pwrite(buf, size, offset), size);
	}
	FILE *handle_() const { return fp_; }
	int error_ = 0; // errno of the first failed write

private:
	size_t note(size_t n, size_t size)
	{
		if (n != size) {
			error_ = errno ? errno : EIO;
			return size;
		}
		return n;
	}
	FILE *fp_;
};

struct rf__module_writer {
	// Declared before out, so the image is closed before its file.
	std::unique_ptr<checked_file> file;
	std::unique_ptr<ImageOutput> out;
	std::string path;
	size_t width, height, nchannels, next_row;
	~rf__module_writer()
	{
		out.reset();
		if (file) {
			FILE *fp = file->handle_();
			file.reset();
			fclose(fp);
		}
	}
};

static void
set_error(char *err, size_t errlen, const char *what, const std::string &path,
          const std::string &reason)
{
	std::string r = reason;

	// OpenImageIO's messages may span lines; a tool message is one line.
	// and one without control bytes, which a file's names may bring.
	for (char &c : r)
		if (c == '\n' || c == '\r')
			c = ' ';
		else if ((unsigned char)c < 0x20 || c == 0x7f)
			c = '?';
	while (!r.empty() && r.back() == ' ')
		r.pop_back();
	if (errlen)
		snprintf(err, errlen, "%s '%s': %s", what, path.c_str(),
		         r.empty() ? "unknown error" : r.c_str());
}

// A message from C strings only, for a handler of an exception, where
// a std::string could throw again.
static void
set_error_c(char *err, size_t errlen, const char *what, const char *path,
            const char *reason)
{
	if (errlen)
		snprintf(err, errlen, "%s '%s': %s", what, path ? path : "",
		         reason && *reason ? reason : "unknown error");
	for (size_t i = 0; errlen && err[i]; i++)
		if (err[i] == '\n' || err[i] == '\r')
			err[i] = ' ';
}

// No exception leaves the module: libreflect and the tools are C, and
// one crossing into them ends the process (std::terminate).  OpenImageIO
// and the standard library throw std::bad_alloc when memory runs out,
// and std::system_error when a thread cannot be made (under ulimit -v,
// reading a TIFF threw "Resource temporarily unavailable" and aborted).
// Each function of the table runs its body through this, which turns an
// exception into a status and a message.
template <typename F>
static int
guarded(char *err, size_t errlen, const char *what, const char *path, F body) noexcept
{
	try {
		return body();
	} catch (const std::bad_alloc &) {
		set_error_c(err, errlen, what, path, "out of memory");
		return RF_ENOMEM;
	} catch (const std::system_error &e) {
		// Threads or memory the system would not give: a system error.
		set_error_c(err, errlen, what, path, e.what());
		return e.code() == std::errc::resource_unavailable_try_again ||
		       e.code() == std::errc::not_enough_memory ? RF_ENOMEM : RF_EIO;
	} catch (const std::exception &e) {
		set_error_c(err, errlen, what, path, e.what());
		return RF_EIMAGE;
	} catch (...) {
		set_error_c(err, errlen, what, path, "unknown error");
		return RF_EIMAGE;
	}
}

// When OpenImageIO cannot open a file, the reason is often the file
// system's (no such directory, permission denied) and its own message
// hides that.  Asks the system with the same access; returns errno, or 0
// when the system would allow it.  A file created only to ask is removed.
static int
system_reason(const char *path, bool write)
{
	FILE *fp;
	int e;

	if (!write) {
		fp = fopen(path, "rb");
		e = errno;
		if (fp)
			fclose(fp);
		return fp ? 0 : e;
	}
	FILE *old = fopen(path, "rb");
	if (old)
		fclose(old);
	fp = fopen(path, "ab");
	e = errno;
	if (!fp)
		return e;
	fclose(fp);
	if (!old)
		remove(path);
	return 0;
}

// Reads MIP level `level` of the first image.
static int
read_level(rf_image **imgp, const char *path, size_t level, rf__image_check_fn *check,
           char *err, size_t errlen)
{
	*imgp = nullptr;
	// Values as stored: no premultiplying of 8- and 16-bit files that
	// keep straight alpha (PNG, TIFF).
	ImageSpec config;
	config.attribute("oiio:UnassociatedAlpha", 1);
	auto in = ImageInput::open(path, &config);
	if (!in) {
		std::string reason = OIIO::geterror();
		int e = system_reason(path, false);

		set_error(err, errlen, "cannot open", path, e ? strerror(e) : reason);
		return RF_EIMAGE;
	}
	if (level > 0 && !in->seek_subimage(0, (int)level)) {
		set_error(err, errlen, "cannot read", path,
		          "no MIP level " + std::to_string(level));
		return RF_EIMAGE;
	}
	const ImageSpec &spec = in->spec();
	if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0 ||
	    spec.depth > 1) {
		set_error(err, errlen, "cannot read", path, "not a 2D image");
		return RF_EIMAGE;
	}
	// The header's size, bounded by libreflect before it is believed.
	size_t n = (size_t)spec.width * (size_t)spec.height;
	int rc = check(path, in->format_name(), (size_t)spec.width, (size_t)spec.height,
	               (size_t)spec.nchannels, err, errlen);
	if (rc < 0)
		return rc;
	std::unique_ptr<rf_image> img(new rf_image);
	img->width = (size_t)spec.width;
	img->height = (size_t)spec.height;
	img->nchannels = (size_t)spec.nchannels;
	img->pixels.resize(n * img->nchannels);
	for (int c = 0; c < spec.nchannels; c++)
		img->names.push_back(c < (int)spec.channelnames.size()
		                     ? spec.channelnames[c] : "c" + std::to_string(c));
	for (const auto &p : spec.extra_attribs)
		if (p.type() == TypeString)
			img->attributes.emplace_back(p.name().string(), p.get_string());
	if (!in->read_image(0, (int)level, 0, spec.nchannels, TypeFloat,
	                    img->pixels.data())) {
		set_error(err, errlen, "cannot read", path, in->geterror());
		return RF_EIMAGE;
	}
	in->close();
	*imgp = img.release();
	return 0;
}

static int
module_read_level(rf_image **imgp, const char *path, size_t level,
                  rf__image_check_fn *check, char *err, size_t errlen)
{
	*imgp = nullptr;
	return guarded(err, errlen, "cannot read", path,
	               [&] { return read_level(imgp, path, level, check, err, errlen); });
}

static void
module_free(rf_image *img)
{
	delete img;
}

static size_t module_width(const rf_image *img) { return img->width; }
static size_t module_height(const rf_image *img) { return img->height; }
static size_t module_nchannels(const rf_image *img) { return img->nchannels; }

static const char *
module_channel(const rf_image *img, size_t i)
{
	return i < img->names.size() ? img->names[i].c_str() : nullptr;
}

static const float *
module_pixels(const rf_image *img)
{
	return img->pixels.data();
}

static const char *
module_attribute(const rf_image *img, const char *name)
{
	for (const auto &a : img->attributes)
		if (a.first == name)
			return a.second.c_str();
	return nullptr;
}

static TypeDesc
oiio_type(enum rf_pixel_type type)
{
	switch (type) {
	case RF_PIXEL_HALF: return TypeDesc::HALF;
	case RF_PIXEL_UINT8: return TypeDesc::UINT8;
	case RF_PIXEL_UINT16: return TypeDesc::UINT16;
	default: return TypeDesc::FLOAT;
	}
}

// Whether this OpenImageIO has a writer for files with the extension ext
// (lowercase), from its lists of formats: asked without creating a writer.
static bool
can_write(const std::string &ext)
{
	std::string exts, writers, format;

	if (!OIIO::getattribute("extension_list", exts) ||
	    !OIIO::getattribute("output_format_list", writers))
		return false;
	// "openexr:exr,sxr;tiff:tif,tiff;..."
	for (size_t p = 0; p < exts.size();) {
		size_t end = exts.find(';', p), colon = exts.find(':', p);
		if (end == std::string::npos)
			end = exts.size();
		if (colon != std::string::npos && colon < end) {
			std::string list = "," + exts.substr(colon + 1, end - colon - 1) + ",";
			if (list.find("," + ext + ",") != std::string::npos) {
				format = exts.substr(p, colon - p);
				break;
			}
		}
		p = end + 1;
	}
	return !format.empty() &&
	       ("," + writers + ",").find("," + format + ",") != std::string::npos;
}

// The extension of a file name in lowercase, "" when it has none.
static std::string
extension(const char *path)
{
	std::string p(path);
	size_t dot = p.rfind('.');

	if (dot == std::string::npos || p.find('/', dot) != std::string::npos)
		return "";
	std::string ext = p.substr(dot + 1);
	for (char &c : ext)
		c = (char)tolower((unsigned char)c);
	return ext;
}

static int
type_for_path(const char *path)
{
	std::string ext = extension(path);
	int type;

	// PFM is left out: OpenImageIO lists it under a format it can write
	// but (2.4) cannot write it.
	if (ext == "exr" || ext == "hdr")
		type = RF_PIXEL_FLOAT;
	else if (ext == "png" || ext == "jpg" || ext == "jpeg" || ext == "tif" ||
	         ext == "tiff" || ext == "bmp" || ext == "tga" || ext == "ppm")
		type = RF_PIXEL_UINT8;
	else
		return -1;
	return can_write(ext) ? type : -1;
}

static int
module_type_for_path(const char *path)
{
	char err[256];
	int rc = guarded(err, sizeof(err), "cannot write", path,
	                 [&] { return type_for_path(path); });

	return rc < 0 ? -1 : rc;
}

static std::string
fixed_date()
{
	const char *env = getenv("SOURCE_DATE_EPOCH");
	char *end = nullptr;
	long long t = env && *env ? strtoll(env, &end, 10) : 0;
	time_t when = (end && *end) || t < 0 ? 0 : (time_t)t;
	struct tm tm;
	char buf[32];

	gmtime_r(&when, &tm);
	strftime(buf, sizeof(buf), "%Y:%m:%d %H:%M:%S", &tm);
	return buf;
}

static int
writer_open(rf__module_writer **wp, const char *path, size_t width,
                     size_t height, size_t nchannels, const char *const *names,
                     enum rf_pixel_type type, char *err, size_t errlen)
{
	*wp = nullptr;
	if (!width || !height || !nchannels || width > INT32_MAX || height > INT32_MAX ||
	    nchannels > 1024) {
		set_error(err, errlen, "cannot write", path, "bad image size");
		return RF_EINVAL;
	}
	// Freed on every way out, an exception's included.
	std::unique_ptr<rf__module_writer> own(new rf__module_writer);
	rf__module_writer *w = own.get();
	w->path = path;
	w->width = width;
	w->height = height;
	w->nchannels = nchannels;
	w->next_row = 0;
	// We open the file ourselves, before anything else, so that the
	// system's reason for a failure is reported and every write checked.
	// Not for TIFF: OpenImageIO 2.4 writes a broken file through a proxy
	// when it adds the EXIF colour space.
	std::string ext = extension(path);
	if (ext != "tif" && ext != "tiff") {
		FILE *fp = fopen(path, "wb");

		if (!fp) {
			set_error(err, errlen, "cannot write", path, strerror(errno));
			return RF_EIO;
		}
		w->file.reset(new (std::nothrow) checked_file(fp));
		if (!w->file) {
			fclose(fp);
			set_error_c(err, errlen, "cannot write", path, "out of memory");
			return RF_ENOMEM;
		}
	}
	w->out = ImageOutput::create(path);
	if (!w->out) {
		set_error(err, errlen, "cannot write", path, OIIO::geterror());
		return RF_EIMAGE;
	}
	if (w->file && (!w->out->supports("ioproxy") ||
	                !w->out->set_ioproxy(w->file.get()))) {
		// No proxy for this format: OpenImageIO opens the file by name.
		FILE *fp = w->file->handle_();

		(void)w->out->geterror();
		w->file.reset();
		fclose(fp);
	}
	ImageSpec spec((int)width, (int)height, (int)nchannels, oiio_type(type));
	if (names) {
		spec.channelnames.clear();
		for (size_t c = 0; c < nchannels; c++)
			spec.channelnames.push_back(names[c]);
		spec.alpha_channel = -1;
		for (size_t c = 0; c < nchannels; c++)
			if (!strcmp(names[c], "A"))
				spec.alpha_channel = (int)c;
	}
	// Formats that carry a date (TIFF's DateTime tag) get a fixed one, so
	// the same pixels make the same bytes: SOURCE_DATE_EPOCH when set, as
	// reproducible builds do, else the epoch itself.
	spec.attribute("DateTime", fixed_date());
	if (type == RF_PIXEL_UINT8 || type == RF_PIXEL_UINT16) {
		spec.attribute("oiio:ColorSpace", "sRGB");
		// Integer files get their alpha as given (straight, not
		// premultiplied): OpenImageIO must not divide by it again.
		spec.attribute("oiio:UnassociatedAlpha", 1);
	}
	if (!w->out->open(path, spec)) {
		std::string reason = w->out->geterror();
		int e = w->file ? w->file->error_ : system_reason(path, true);

		// A file the system will not let us write is a system error.
		set_error(err, errlen, "cannot write", path, e ? strerror(e) : reason);
		return e ? RF_EIO : RF_EIMAGE;
	}
	*wp = own.release();
	return 0;
}

static int
writer_write_rows(rf__module_writer *w, size_t y, size_t nrows,
                           const float *pixels, char *err, size_t errlen)
{
	if (y != w->next_row || y + nrows > w->height) {
		set_error(err, errlen, "cannot write", w->path, "rows out of order");
		return RF_EINVAL;
	}
	errno = 0;
	if (!w->out->write_scanlines((int)y, (int)(y + nrows), 0, TypeFloat, pixels)) {
		std::string reason = w->out->geterror();
		// Without a proxy (TIFF) the system's reason is errno, when it
		// is one a write gives.
		int e = w->file ? w->file->error_ : errno == ENOSPC || errno == EDQUOT ||
		                                    errno == EFBIG || errno == EIO ? errno : 0;

		if (e) {
			set_error(err, errlen, "cannot write", w->path, strerror(e));
			return RF_EIO;
		}
		set_error(err, errlen, "cannot write", w->path, reason);
		return RF_EIMAGE;
	}
	if (w->file && w->file->error_) {
		set_error(err, errlen, "cannot write", w->path, strerror(w->file->error_));
		return RF_EIO;
	}
	w->next_row += nrows;
	return 0;
}

static int
writer_close(rf__module_writer *w, char *err, size_t errlen)
{
	int rc = 0;

	if (!w)
		return 0;
	// Freed on every way out, an exception's included.
	std::unique_ptr<rf__module_writer> own(w);
	if (w->next_row != w->height) {
		set_error(err, errlen, "cannot write", w->path, "image is incomplete");
		rc = RF_EINVAL;
	}
	if (!w->out->close() && !rc) {
		std::string reason = w->out->geterror();

		if (w->file && w->file->error_) {
			set_error(err, errlen, "cannot write", w->path,
			          strerror(w->file->error_));
			rc = RF_EIO;
		} else {
			set_error(err, errlen, "cannot write", w->path, reason);
			rc = RF_EIMAGE;
		}
	}
	w->out.reset();
	if (w->file) {
		FILE *fp = w->file->handle_();
		int e = w->file->error_;

		w->file.reset();
		if (fflush(fp) != 0 || ferror(fp))
			e = e ? e : (errno ? errno : EIO);
		if (fclose(fp) != 0)
			e = e ? e : errno;
		if (e && !rc) {
			set_error(err, errlen, "cannot write", w->path, strerror(e));
			rc = RF_EIO;
		}
	}
	return rc;
}

// MIP-mapped files (OpenEXR keeps MIP levels only in tiled files).
static int
write_levels(const char *path, size_t nlevels, const size_t *w, const size_t *h,
                      size_t nch, const char *const *names, const float *const *pixels,
                      const char *const *attributes, enum rf_pixel_type type,
                      char *err, size_t errlen)
{
	// The file is written through a checked proxy, as module_writer_open
	// writes: OpenEXR's tiled writer, told by OpenImageIO's stream that a
	// write failed (a full disk), threw from a tile while its other
	// threads waited on that tile's semaphore, and waited for ever
	// (OpenEXR 3.1, TiledOutputFile::writeTiles).  The proxy takes every
	// write and keeps the first error, which the close reports.
	FILE *fp = fopen(path, "wb");
	if (!fp) {
		set_error(err, errlen, "cannot write", path, strerror(errno));
		return RF_EIO;
	}
	std::unique_ptr<checked_file> file;
	try {
		file.reset(new checked_file(fp));
	} catch (...) {
		fclose(fp);
		throw;
	}
	// Closed before the file: declared after it.
	auto out = ImageOutput::create(path);
	auto fail = [&](int rc, const std::string &reason) {
		out.reset();
		int e = file->error_;
		file.reset();
		fclose(fp);
		set_error(err, errlen, "cannot write", path, e ? strerror(e) : reason);
		return e ? RF_EIO : rc;
	};

	if (!out)
		return fail(RF_EIMAGE, OIIO::geterror());
	if (nlevels > 1 && !out->supports("mipmap"))
		return fail(RF_EIMAGE, "this file type holds no MIP levels (use .exr)");
	if (!out->supports("ioproxy") || !out->set_ioproxy(file.get()))
		return fail(RF_EIMAGE, "this file type cannot be written through a checked "
		                       "file (use .exr)");
	for (size_t k = 0; k < nlevels; k++) {
		TypeDesc t = type == RF_PIXEL_HALF ? TypeDesc::HALF : TypeDesc::FLOAT;
		ImageSpec spec((int)w[k], (int)h[k], (int)nch, t);

		spec.channelnames.clear();
		for (size_t c = 0; c < nch; c++)
			spec.channelnames.push_back(names[c]);
		if (nlevels > 1) {
			// OpenEXR keeps MIP levels only in tiled files.
			spec.tile_width = spec.tile_height = 64;
			spec.attribute("openexr:roundingmode", 0); // ROUND_DOWN
		}
		for (size_t a = 0; attributes && attributes[a]; a += 2)
			spec.attribute(attributes[a], attributes[a + 1]);
		// Else OpenEXR's capDate is the time of writing (see
		// module_writer_open).
		spec.attribute("DateTime", fixed_date());
		if (!out->open(path, spec, k ? ImageOutput::AppendMIPLevel : ImageOutput::Create) ||
		    !out->write_image(TypeFloat, pixels[k]))
			return fail(RF_EIMAGE, out->geterror());
	}
	if (!out->close())
		return fail(RF_EIMAGE, out->geterror());
	out.reset();
	int e = file->error_;
	file.reset();
	if (fflush(fp) != 0 || ferror(fp))
		e = e ? e : (errno ? errno : EIO);
	if (fclose(fp) != 0)
		e = e ? e : errno;
	if (e) {
		set_error(err, errlen, "cannot write", path, strerror(e));
		return RF_EIO;
	}
	return 0;
}

static int
count_levels(const char *path, size_t *nlevels, char *err, size_t errlen)
{
	auto in = ImageInput::open(path);
	size_t n = 1;

	if (!in) {
		set_error(err, errlen, "cannot open", path, OIIO::geterror());
		return RF_EIMAGE;
	}
	while (n < 32 && in->seek_subimage(0, (int)n))
		n++;
	*nlevels = n;
	return 0;
}

static int
module_count_levels(const char *path, size_t *nlevels, char *err, size_t errlen)
{
	return guarded(err, errlen, "cannot open", path,
	               [&] { return count_levels(path, nlevels, err, errlen); });
}

static int
module_writer_open(rf__module_writer **wp, const char *path, size_t width, size_t height,
                   size_t nchannels, const char *const *names, enum rf_pixel_type type,
                   char *err, size_t errlen)
{
	*wp = nullptr;
	return guarded(err, errlen, "cannot write", path, [&] {
		return writer_open(wp, path, width, height, nchannels, names, type, err,
		                   errlen);
	});
}

static int
module_writer_write_rows(rf__module_writer *w, size_t y, size_t nrows,
                         const float *pixels, char *err, size_t errlen)
{
	return guarded(err, errlen, "cannot write", w->path.c_str(), [&] {
		return writer_write_rows(w, y, nrows, pixels, err, errlen);
	});
}

// Frees the writer whatever happens: the caller forgets it.
static int
module_writer_close(rf__module_writer *w, char *err, size_t errlen)
{
	char path[4096];

	if (!w)
		return 0;
	// Kept for a message after the writer is gone.
	snprintf(path, sizeof(path), "%s", w->path.c_str());
	return guarded(err, errlen, "cannot write", path,
	               [&] { return writer_close(w, err, errlen); });
}

static int
module_write_levels(const char *path, size_t nlevels, const size_t *w, const size_t *h,
                    size_t nch, const char *const *names, const float *const *pixels,
                    const char *const *attributes, enum rf_pixel_type type, char *err,
                    size_t errlen)
{
	return guarded(err, errlen, "cannot write", path, [&] {
		return write_levels(path, nlevels, w, h, nch, names, pixels, attributes,
		                    type, err, errlen);
	});
}

// The module's one exported symbol: its functions, for libreflect to call.
static const struct rf__image_api api = {
	sizeof(struct rf__image_api),
	module_read_level,
	module_count_levels,
	module_free,
	module_width,
	module_height,
	module_nchannels,
	module_channel,
	module_pixels,
	module_attribute,
	module_type_for_path,
	module_writer_open,
	module_writer_write_rows,
	module_writer_close,
	module_write_levels,
};

extern "C" __attribute__((visibility("default"))) const struct rf__image_api *
rf__image_module(void)
{
	return &api;
}
