/* table_end.h: the end of a table (see table_rows.h): every row macro is undefined again. */
#undef TRIBO_PARAMETER
#undef TRIBO_SAME_PARAMETER
#undef TRIBO_MAPS
#undef TRIBO_DERIVES
#undef TRIBO_TIME
#undef TRIBO_INPUT
#undef TRIBO_OUTPUT
#undef TRIBO_CALCULATED
#undef TRIBO_SEGMENTS
#undef TRIBO_UNIT
#undef TRIBO_DISPLAY_UNIT
#undef TRIBO_ENUMERATION
#undef TRIBO_ENUM_ITEM
#undef TRIBO_RETIRED
