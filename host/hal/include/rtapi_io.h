/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * rtapi_io.h - x86 port I/O for components, with LinuxCNC's names:
 * rtapi_request_region() / rtapi_release_region() ask the kernel for
 * access to a range of I/O ports (ioperm; needs root or CAP_SYS_RAWIO),
 * rtapi_inb() / rtapi_outb() and friends access them.  On other
 * architectures the region calls fail and the accessors do nothing.
 */
#ifndef HM_RTAPI_IO_H
#define HM_RTAPI_IO_H

#if defined(__x86_64__) || defined(__i386__)
#include <sys/io.h>
#define RTAPI_HAVE_PORT_IO 1
#else
#define RTAPI_HAVE_PORT_IO 0
#endif

/* Non-NULL when access to ports base .. base+size-1 was granted, NULL
 * otherwise (as LinuxCNC's, which returns the kernel's resource). */
static inline void *rtapi_request_region(unsigned long rtapi_base_, unsigned long rtapi_size_,
                                         const char *rtapi_name_)
{
    (void)rtapi_name_;
#if RTAPI_HAVE_PORT_IO
    if (ioperm(rtapi_base_, rtapi_size_, 1) == 0)
        return (void *)(unsigned long)(rtapi_base_ | 1ul); /* any non-NULL token */
#else
    (void)rtapi_base_;
    (void)rtapi_size_;
#endif
    return (void *)0;
}

static inline void rtapi_release_region(unsigned long rtapi_base_, unsigned long rtapi_size_)
{
#if RTAPI_HAVE_PORT_IO
    (void)ioperm(rtapi_base_, rtapi_size_, 0);
#else
    (void)rtapi_base_;
    (void)rtapi_size_;
#endif
}

#if RTAPI_HAVE_PORT_IO
#define rtapi_inb(port) inb(port)
#define rtapi_inw(port) inw(port)
#define rtapi_inl(port) inl(port)
#define rtapi_outb(value, port) outb((value), (port))
#define rtapi_outw(value, port) outw((value), (port))
#define rtapi_outl(value, port) outl((value), (port))
#else
#define rtapi_inb(port) ((void)(port), 0)
#define rtapi_inw(port) ((void)(port), 0)
#define rtapi_inl(port) ((void)(port), 0)
#define rtapi_outb(value, port) ((void)(value), (void)(port))
#define rtapi_outw(value, port) ((void)(value), (void)(port))
#define rtapi_outl(value, port) ((void)(value), (void)(port))
#endif

#endif /* HM_RTAPI_IO_H */
