/*
 * fmi2.c: the FMI 2.0 co-simulation entry points, translated to the instance layer.
 *
 * Every function of fmi2Functions.h is here (importers resolve all of them); those
 * behind a capability this FMU does not declare return fmi2Error with the reason.
 */
#include "fmi2Functions.h"

#include "instance.h"
#include "instantiation_token.h"

#define INST(c) ((fmu_instance *)(c))
#define STATUS(s) ((fmi2Status)(s))
#define UNUSED(x) (void)(x)

/* fmi2's logger formats its message like printf: a '%' in ours must come out as is. */
static void log_sink(const fmu_logger *logger, const char *instance_name, fmu_status status,
                     const char *category, const char *message)
{
    const fmi2CallbackLogger log = (fmi2CallbackLogger)logger->importer_logger;
    char escaped[2048];
    size_t j = 0;
    for (size_t i = 0; message[i] && j + 2 < sizeof escaped; i++) {
        if (message[i] == '%')
            escaped[j++] = '%';
        escaped[j++] = message[i];
    }
    escaped[j] = '\0';
    log(logger->environment, instance_name, STATUS(status), category, escaped);
}

/* ---- common functions ------------------------------------------------------------ */

const char *fmi2GetTypesPlatform(void) { return fmi2TypesPlatform; }

const char *fmi2GetVersion(void) { return fmi2Version; }

fmi2Status fmi2SetDebugLogging(fmi2Component c, fmi2Boolean loggingOn, size_t nCategories,
                               const fmi2String categories[])
{
    return STATUS(fmu_set_debug_logging(INST(c), __func__, loggingOn, nCategories, categories));
}

fmi2Component fmi2Instantiate(fmi2String instanceName, fmi2Type fmuType, fmi2String fmuGUID,
                              fmi2String fmuResourceLocation,
                              const fmi2CallbackFunctions *functions, fmi2Boolean visible,
                              fmi2Boolean loggingOn)
{
    UNUSED(fmuResourceLocation); /* the FMU has no resources */
    UNUSED(visible);
    fmu_logger logger = {0};
    if (functions && functions->logger) {
        logger.sink = log_sink;
        logger.importer_logger = (fmu_any_function)functions->logger;
        logger.environment = functions->componentEnvironment;
    }
    if (fmuType != fmi2CoSimulation) {
        fmu_refuse_instantiation(&logger, __func__, instanceName,
                                 "this FMU implements co-simulation only");
        return NULL;
    }
    return fmu_instantiate(2, __func__, instanceName, fmuGUID, FMU_INSTANTIATION_TOKEN, &logger,
                           loggingOn);
}

void fmi2FreeInstance(fmi2Component c) { fmu_free(INST(c)); }

fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean toleranceDefined,
                               fmi2Real tolerance, fmi2Real startTime,
                               fmi2Boolean stopTimeDefined, fmi2Real stopTime)
{
    return STATUS(fmu_setup_experiment(INST(c), __func__, toleranceDefined, tolerance, startTime,
                                       stopTimeDefined, stopTime));
}

fmi2Status fmi2EnterInitializationMode(fmi2Component c)
{
    return STATUS(fmu_enter_initialization(INST(c), __func__));
}

fmi2Status fmi2ExitInitializationMode(fmi2Component c)
{
    return STATUS(fmu_exit_initialization(INST(c), __func__));
}

fmi2Status fmi2Terminate(fmi2Component c) { return STATUS(fmu_terminate(INST(c), __func__)); }

fmi2Status fmi2Reset(fmi2Component c) { return STATUS(fmu_reset(INST(c), __func__)); }

/* ---- values ---------------------------------------------------------------------- */

#define REAL_TYPES FMU_TYPE_BIT(FMU_TYPE_REAL)
/* enumerations are Integers to FMI 2.0's functions */
#define INTEGER_TYPES \
    (FMU_TYPE_BIT(FMU_TYPE_INTEGER) | FMU_TYPE_BIT(FMU_TYPE_COUNT) | FMU_TYPE_BIT(FMU_TYPE_ENUMERATION))
#define BOOLEAN_TYPES FMU_TYPE_BIT(FMU_TYPE_BOOLEAN)

fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                       fmi2Real value[])
{
    return STATUS(fmu_get(INST(c), __func__, REAL_TYPES, FMU_C_DOUBLE, vr, nvr, value, nvr));
}

fmi2Status fmi2GetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                          fmi2Integer value[])
{
    return STATUS(fmu_get(INST(c), __func__, INTEGER_TYPES, FMU_C_INT, vr, nvr, value, nvr));
}

fmi2Status fmi2GetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                          fmi2Boolean value[])
{
    return STATUS(fmu_get(INST(c), __func__, BOOLEAN_TYPES, FMU_C_INT, vr, nvr, value, nvr));
}

fmi2Status fmi2GetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                         fmi2String value[])
{
    return STATUS(fmu_get(INST(c), __func__, 0, FMU_C_NONE, vr, nvr, value, nvr));
}

fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                       const fmi2Real value[])
{
    return STATUS(fmu_set(INST(c), __func__, REAL_TYPES, FMU_C_DOUBLE, vr, nvr, value, nvr));
}

fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                          const fmi2Integer value[])
{
    return STATUS(fmu_set(INST(c), __func__, INTEGER_TYPES, FMU_C_INT, vr, nvr, value, nvr));
}

fmi2Status fmi2SetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                          const fmi2Boolean value[])
{
    return STATUS(fmu_set(INST(c), __func__, BOOLEAN_TYPES, FMU_C_INT, vr, nvr, value, nvr));
}

fmi2Status fmi2SetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                         const fmi2String value[])
{
    return STATUS(fmu_set(INST(c), __func__, 0, FMU_C_NONE, vr, nvr, value, nvr));
}

/* ---- FMU states ------------------------------------------------------------------ */

fmi2Status fmi2GetFMUstate(fmi2Component c, fmi2FMUstate *FMUstate)
{
    fmu_state *s = FMUstate ? *FMUstate : NULL;
    const fmu_status st = fmu_state_get(INST(c), __func__, FMUstate ? &s : NULL);
    if (FMUstate)
        *FMUstate = s;
    return STATUS(st);
}

fmi2Status fmi2SetFMUstate(fmi2Component c, fmi2FMUstate FMUstate)
{
    return STATUS(fmu_state_set(INST(c), __func__, FMUstate));
}

fmi2Status fmi2FreeFMUstate(fmi2Component c, fmi2FMUstate *FMUstate)
{
    fmu_state *s = FMUstate ? *FMUstate : NULL;
    const fmu_status st = fmu_state_free(INST(c), __func__, &s);
    if (FMUstate)
        *FMUstate = s;
    return STATUS(st);
}

fmi2Status fmi2SerializedFMUstateSize(fmi2Component c, fmi2FMUstate FMUstate, size_t *size)
{
    return STATUS(fmu_state_size(INST(c), __func__, FMUstate, size));
}

fmi2Status fmi2SerializeFMUstate(fmi2Component c, fmi2FMUstate FMUstate,
                                 fmi2Byte serializedState[], size_t size)
{
    return STATUS(fmu_state_serialize(INST(c), __func__, FMUstate, serializedState, size));
}

fmi2Status fmi2DeSerializeFMUstate(fmi2Component c, const fmi2Byte serializedState[],
                                   size_t size, fmi2FMUstate *FMUstate)
{
    fmu_state *s = NULL;
    const fmu_status st = fmu_state_deserialize(INST(c), __func__, serializedState, size,
                                                FMUstate ? &s : NULL);
    if (FMUstate && st == FMU_OK)
        *FMUstate = s;
    return STATUS(st);
}

fmi2Status fmi2GetDirectionalDerivative(fmi2Component c, const fmi2ValueReference vUnknown_ref[],
                                        size_t nUnknown, const fmi2ValueReference vKnown_ref[],
                                        size_t nKnown, const fmi2Real dvKnown[],
                                        fmi2Real dvUnknown[])
{
    UNUSED(vUnknown_ref), UNUSED(nUnknown), UNUSED(vKnown_ref), UNUSED(nKnown);
    UNUSED(dvKnown), UNUSED(dvUnknown);
    return STATUS(fmu_refuse(INST(c), __func__, "providesDirectionalDerivative is false"));
}

/* ---- model exchange: not implemented ------------------------------------------ */

#define NOT_MODEL_EXCHANGE "this FMU implements co-simulation only"

fmi2Status fmi2EnterEventMode(fmi2Component c)
{
    return STATUS(fmu_refuse(INST(c), __func__, NOT_MODEL_EXCHANGE));
}

fmi2Status fmi2NewDiscreteStates(fmi2Component c, fmi2EventInfo *fmi2eventInfo)
{
    UNUSED(fmi2eventInfo);
    return STATUS(fmu_refuse(INST(c), __func__, NOT_MODEL_EXCHANGE));
}

fmi2Status fmi2EnterContinuousTimeMode(fmi2Component c)
{
    return STATUS(fmu_refuse(INST(c), __func__, NOT_MODEL_EXCHANGE));
}

fmi2Status fmi2CompletedIntegratorStep(fmi2Component c,
                                       fmi2Boolean noSetFMUStatePriorToCurrentPoint,
                                       fmi2Boolean *enterEventMode,
                                       fmi2Boolean *terminateSimulation)
{
    UNUSED(noSetFMUStatePriorToCurrentPoint), UNUSED(enterEventMode), UNUSED(terminateSimulation);
    return STATUS(fmu_refuse(INST(c), __func__, NOT_MODEL_EXCHANGE));
}

fmi2Status fmi2SetTime(fmi2Component c, fmi2Real time)
{
    UNUSED(time);
    return STATUS(fmu_refuse(INST(c), __func__, NOT_MODEL_EXCHANGE));
}

fmi2Status fmi2SetContinuousStates(fmi2Component c, const fmi2Real x[], size_t nx)
{
    UNUSED(x), UNUSED(nx);
    return STATUS(fmu_refuse(INST(c), __func__, NOT_MODEL_EXCHANGE));
}

fmi2Status fmi2GetDerivatives(fmi2Component c, fmi2Real derivatives[], size_t nx)
{
    UNUSED(derivatives), UNUSED(nx);
    return STATUS(fmu_refuse(INST(c), __func__, NOT_MODEL_EXCHANGE));
}

fmi2Status fmi2GetEventIndicators(fmi2Component c, fmi2Real eventIndicators[], size_t ni)
{
    UNUSED(eventIndicators), UNUSED(ni);
    return STATUS(fmu_refuse(INST(c), __func__, NOT_MODEL_EXCHANGE));
}

fmi2Status fmi2GetContinuousStates(fmi2Component c, fmi2Real x[], size_t nx)
{
    UNUSED(x), UNUSED(nx);
    return STATUS(fmu_refuse(INST(c), __func__, NOT_MODEL_EXCHANGE));
}

fmi2Status fmi2GetNominalsOfContinuousStates(fmi2Component c, fmi2Real x_nominal[], size_t nx)
{
    UNUSED(x_nominal), UNUSED(nx);
    return STATUS(fmu_refuse(INST(c), __func__, NOT_MODEL_EXCHANGE));
}

/* ---- co-simulation ------------------------------------------------------------------ */

fmi2Status fmi2SetRealInputDerivatives(fmi2Component c, const fmi2ValueReference vr[],
                                       size_t nvr, const fmi2Integer order[],
                                       const fmi2Real value[])
{
    UNUSED(vr), UNUSED(nvr), UNUSED(order), UNUSED(value);
    return STATUS(fmu_refuse(INST(c), __func__,
                             "canInterpolateInputs is false: inputs are held over each step"));
}

fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference vr[],
                                        size_t nvr, const fmi2Integer order[], fmi2Real value[])
{
    UNUSED(vr), UNUSED(nvr), UNUSED(order), UNUSED(value);
    return STATUS(fmu_refuse(INST(c), __func__, "maxOutputDerivativeOrder is 0"));
}

fmi2Status fmi2DoStep(fmi2Component c, fmi2Real currentCommunicationPoint,
                      fmi2Real communicationStepSize,
                      fmi2Boolean noSetFMUStatePriorToCurrentPoint)
{
    UNUSED(noSetFMUStatePriorToCurrentPoint); /* states cost nothing to keep */
    double reached;
    int early_return; /* never allowed in FMI 2.0: a step that ends early is discarded */
    int terminate;    /* the particle left the chute: fmi2Terminated after the fmi2Discard */
    return STATUS(fmu_do_step(INST(c), __func__, currentCommunicationPoint,
                              communicationStepSize, &reached, &early_return, &terminate));
}

fmi2Status fmi2CancelStep(fmi2Component c)
{
    return STATUS(fmu_refuse(INST(c), __func__, "fmi2DoStep never runs asynchronously"));
}

/* The status inquiries: those that make sense for a step that runs synchronously (after
   fmi2Discard: the time reached, and whether the FMU asks to terminate: it does once the
   particle has left the chute). */

fmi2Status fmi2GetStatus(fmi2Component c, const fmi2StatusKind s, fmi2Status *value)
{
    UNUSED(s), UNUSED(value);
    return STATUS(fmu_refuse(INST(c), __func__, "fmi2DoStep never returns fmi2Pending"));
}

fmi2Status fmi2GetRealStatus(fmi2Component c, const fmi2StatusKind s, fmi2Real *value)
{
    if (!c || s != fmi2LastSuccessfulTime || !value)
        return STATUS(fmu_refuse(INST(c), __func__,
                                 "only fmi2LastSuccessfulTime is available, into a non-NULL value"));
    *value = fmu_time(INST(c));
    return fmi2OK;
}

fmi2Status fmi2GetIntegerStatus(fmi2Component c, const fmi2StatusKind s, fmi2Integer *value)
{
    UNUSED(s), UNUSED(value);
    return STATUS(fmu_refuse(INST(c), __func__, "there is no integer status"));
}

fmi2Status fmi2GetBooleanStatus(fmi2Component c, const fmi2StatusKind s, fmi2Boolean *value)
{
    if (!c || s != fmi2Terminated || !value)
        return STATUS(fmu_refuse(INST(c), __func__,
                                 "only fmi2Terminated is available, into a non-NULL value"));
    *value = fmu_exited(INST(c)) ? fmi2True : fmi2False;
    return fmi2OK;
}

fmi2Status fmi2GetStringStatus(fmi2Component c, const fmi2StatusKind s, fmi2String *value)
{
    UNUSED(s), UNUSED(value);
    return STATUS(fmu_refuse(INST(c), __func__, "fmi2DoStep never returns fmi2Pending"));
}
