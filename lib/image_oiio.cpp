// The bridge from OpenImageIO (C++) to libreflect's C image API.
#include <OpenImageIO/imageio.h>

#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

extern "C" {
#include "internal.h"
}

using namespace OIIO;

struct rf_image {
	size_t width, height, nchannels;
	std::vector<float> pixels;
	std::vector<std::string> names;
	std::vector<std::pair<std::string, std::string>> attributes;
};

struct rf_image_writer {
	std::unique_ptr<ImageOutput> out;
	std::string path;
	size_t width, height, nchannels, next_row;
};

static void
set_error(char *err, size_t errlen, const char *what, const std::string &path,
          const std::string &reason)
{
	std::string r = reason;

	// OpenImageIO's messages may span lines; a tool message is one line.
	for (char &c : r)
		if (c == '\n' || c == '\r')
			c = ' ';
	while (!r.empty() && r.back() == ' ')
		r.pop_back();
	rf__format(err, errlen, "%s '%s': %s", what, path.c_str(),
	           r.empty() ? "unknown error" : r.c_str());
}

extern "C" int
rf_image_read(rf_image **imgp, const char *path, char *err, size_t errlen)
{
	*imgp = nullptr;
	auto in = ImageInput::open(path);
	if (!in) {
		set_error(err, errlen, "cannot open", path, OIIO::geterror());
		return RF_EIMAGE;
	}
	const ImageSpec &spec = in->spec();
	if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0 ||
	    spec.depth > 1) {
		set_error(err, errlen, "cannot read", path, "not a 2D image");
		return RF_EIMAGE;
	}
	size_t n = (size_t)spec.width * (size_t)spec.height;
	if (n > ((size_t)1 << 31) / (size_t)spec.nchannels) {
		set_error(err, errlen, "cannot read", path, "image too large");
		return RF_ETOOBIG;
	}
	rf_image *img = new (std::nothrow) rf_image;
	if (!img)
		return RF_ENOMEM;
	img->width = (size_t)spec.width;
	img->height = (size_t)spec.height;
	img->nchannels = (size_t)spec.nchannels;
	try {
		img->pixels.resize(n * img->nchannels);
	} catch (...) {
		delete img;
		return RF_ENOMEM;
	}
	for (int c = 0; c < spec.nchannels; c++)
		img->names.push_back(c < (int)spec.channelnames.size()
		                     ? spec.channelnames[c] : "c" + std::to_string(c));
	for (const auto &p : spec.extra_attribs)
		if (p.type() == TypeString)
			img->attributes.emplace_back(p.name().string(), p.get_string());
	if (!in->read_image(0, 0, 0, spec.nchannels, TypeFloat, img->pixels.data())) {
		set_error(err, errlen, "cannot read", path, in->geterror());
		delete img;
		return RF_EIMAGE;
	}
	in->close();
	*imgp = img;
	return 0;
}

extern "C" void
rf_image_free(rf_image *img)
{
	delete img;
}

extern "C" size_t rf_image_width(const rf_image *img) { return img->width; }
extern "C" size_t rf_image_height(const rf_image *img) { return img->height; }
extern "C" size_t rf_image_nchannels(const rf_image *img) { return img->nchannels; }

extern "C" const char *
rf_image_channel(const rf_image *img, size_t i)
{
	return i < img->names.size() ? img->names[i].c_str() : nullptr;
}

extern "C" const float *
rf_image_pixels(const rf_image *img)
{
	return img->pixels.data();
}

extern "C" const char *
rf_image_attribute(const rf_image *img, const char *name)
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

extern "C" int
rf_image_type_for_path(const char *path)
{
	std::string p(path);
	size_t dot = p.rfind('.');
	if (dot == std::string::npos)
		return -1;
	std::string ext = p.substr(dot + 1);
	for (char &c : ext)
		c = (char)tolower((unsigned char)c);
	if (ext == "exr" || ext == "hdr" || ext == "pfm")
		return RF_PIXEL_FLOAT;
	if (ext == "png" || ext == "jpg" || ext == "jpeg" || ext == "tif" ||
	    ext == "tiff" || ext == "bmp" || ext == "tga" || ext == "ppm")
		return RF_PIXEL_UINT8;
	return -1;
}

extern "C" int
rf_image_writer_open(rf_image_writer **wp, const char *path, size_t width,
                     size_t height, size_t nchannels, const char *const *names,
                     enum rf_pixel_type type, char *err, size_t errlen)
{
	*wp = nullptr;
	if (!width || !height || !nchannels || width > INT32_MAX || height > INT32_MAX ||
	    nchannels > 1024) {
		set_error(err, errlen, "cannot write", path, "bad image size");
		return RF_EINVAL;
	}
	auto out = ImageOutput::create(path);
	if (!out) {
		set_error(err, errlen, "cannot write", path, OIIO::geterror());
		return RF_EIMAGE;
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
	if (type == RF_PIXEL_UINT8 || type == RF_PIXEL_UINT16)
		spec.attribute("oiio:ColorSpace", "sRGB");
	if (!out->open(path, spec)) {
		set_error(err, errlen, "cannot write", path, out->geterror());
		return RF_EIMAGE;
	}
	rf_image_writer *w = new (std::nothrow) rf_image_writer;
	if (!w)
		return RF_ENOMEM;
	w->out = std::move(out);
	w->path = path;
	w->width = width;
	w->height = height;
	w->nchannels = nchannels;
	w->next_row = 0;
	*wp = w;
	return 0;
}

extern "C" int
rf_image_writer_write_rows(rf_image_writer *w, size_t y, size_t nrows,
                           const float *pixels, char *err, size_t errlen)
{
	if (y != w->next_row || y + nrows > w->height) {
		set_error(err, errlen, "cannot write", w->path, "rows out of order");
		return RF_EINVAL;
	}
	if (!w->out->write_scanlines((int)y, (int)(y + nrows), 0, TypeFloat, pixels)) {
		set_error(err, errlen, "cannot write", w->path, w->out->geterror());
		return RF_EIMAGE;
	}
	w->next_row += nrows;
	return 0;
}

extern "C" int
rf_image_writer_close(rf_image_writer *w, char *err, size_t errlen)
{
	int rc = 0;

	if (!w)
		return 0;
	if (w->next_row != w->height) {
		set_error(err, errlen, "cannot write", w->path, "image is incomplete");
		rc = RF_EINVAL;
	}
	if (!w->out->close() && !rc) {
		set_error(err, errlen, "cannot write", w->path, w->out->geterror());
		rc = RF_EIMAGE;
	}
	delete w;
	return rc;
}
