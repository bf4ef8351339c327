/* Test-only bcryptprimitives.dll for Wine 8 (Debian 12), which lacks it. Rust's std for
 * x86_64-pc-windows-gnu (>= 1.78) imports ProcessPrng from it; Windows 10/11 ship the real
 * DLL, so this shim goes into the Wine prefix's system32 by scripts/test-win64.sh and never
 * into an FMU. */
#include <windows.h>
#define SystemFunction036 NTAPI SystemFunction036
#include <ntsecapi.h>
#undef SystemFunction036

__declspec(dllexport) BOOL WINAPI ProcessPrng(PBYTE data, SIZE_T len) {
    while (len) {
        ULONG chunk = len > 0x10000000 ? 0x10000000 : (ULONG)len;
        if (!RtlGenRandom(data, chunk)) return FALSE;
        data += chunk;
        len -= chunk;
    }
    return TRUE;
}
