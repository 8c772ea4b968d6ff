/* Status codes and their messages, and the messages the library formats. */
#include <stdio.h>

#include "util/util.h"

const char *
rf_strerror(int status)
{
	switch (status) {
	case RF_OK:
		return "success";
#define RF_STATUS_MSG(name, msg)                                           \
	case RF_E##name:                                                    \
		return msg;
		RF_STATUS_MAP(RF_STATUS_MSG)
#undef RF_STATUS_MSG
	}
	return "unknown error";
}

const char *
rf_status_name(int status)
{
	switch (status) {
	case RF_OK:
		return "RF_OK";
#define RF_STATUS_NAME(name, msg)                                          \
	case RF_E##name:                                                    \
		return "RF_E" #name;
		RF_STATUS_MAP(RF_STATUS_NAME)
#undef RF_STATUS_NAME
	}
	return "RF_E?";
}

void
rf__printable(char *s)
{
	for (; *s; s++)
		if ((unsigned char)*s < 0x20 || *s == 0x7f)
			*s = '?';
}

void
rf__format(char *buf, size_t size, const char *fmt, ...)
{
	va_list ap;

	if (!size)
		return;
	va_start(ap, fmt);
	vsnprintf(buf, size, fmt, ap);
	va_end(ap);
	rf__printable(buf);
}
