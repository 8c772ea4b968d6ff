#include "reflect/reflect.h"

unsigned
rf_version(void)
{
	return RF_VERSION_HEX;
}

const char *
rf_version_string(void)
{
	return RF_VERSION_STRING;
}
