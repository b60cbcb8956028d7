/*
 * fmi3.c: the FMI 3.0 co-simulation entry points, translated to the instance layer.
 *
 * Every function of fmi3Functions.h is here (importers resolve all of them); those
 * behind a capability this FMU does not declare return fmi3Error with the reason.
 */
#include "fmi3Functions.h"

#include "instance.h"
#include "instantiation_token.h"

#define INST(c) ((fmu_instance *)(c))
#define STATUS(s) ((fmi3Status)(s))
#define UNUSED(x) (void)(x)

static void log_sink(const fmu_logger *logger, const char *instance_name, fmu_status status,
                     const char *category, const char *message)
{
    UNUSED(instance_name); /* fmi3's logger knows its instance by the environment */
    const fmi3LogMessageCallback log = (fmi3LogMessageCallback)logger->importer_logger;
    log(logger->environment, STATUS(status), category, message);
}

static fmu_logger logger_of(fmi3InstanceEnvironment environment, fmi3LogMessageCallback log)
{
    fmu_logger logger = {0};
    if (log) {
        logger.sink = log_sink;
        logger.importer_logger = (fmu_any_function)log;
        logger.environment = environment;
    }
    return logger;
}

/* ---- common functions ------------------------------------------------------------ */

const char *fmi3GetVersion(void) { return fmi3Version; }

fmi3Status fmi3SetDebugLogging(fmi3Instance instance, fmi3Boolean loggingOn, size_t nCategories,
                               const fmi3String categories[])
{
    return STATUS(fmu_set_debug_logging(INST(instance), __func__, loggingOn, nCategories, categories));
}

fmi3Instance fmi3InstantiateModelExchange(fmi3String instanceName, fmi3String instantiationToken,
                                          fmi3String resourcePath, fmi3Boolean visible,
                                          fmi3Boolean loggingOn,
                                          fmi3InstanceEnvironment instanceEnvironment,
                                          fmi3LogMessageCallback logMessage)
{
    UNUSED(instantiationToken), UNUSED(resourcePath), UNUSED(visible), UNUSED(loggingOn);
    const fmu_logger logger = logger_of(instanceEnvironment, logMessage);
    fmu_refuse_instantiation(&logger, __func__, instanceName,
                             "this FMU implements co-simulation only");
    return NULL;
}

fmi3Instance fmi3InstantiateCoSimulation(fmi3String instanceName, fmi3String instantiationToken,
                                         fmi3String resourcePath, fmi3Boolean visible,
                                         fmi3Boolean loggingOn, fmi3Boolean eventModeUsed,
                                         fmi3Boolean earlyReturnAllowed,
                                         const fmi3ValueReference requiredIntermediateVariables[],
                                         size_t nRequiredIntermediateVariables,
                                         fmi3InstanceEnvironment instanceEnvironment,
                                         fmi3LogMessageCallback logMessage,
                                         fmi3IntermediateUpdateCallback intermediateUpdate)
{
    UNUSED(resourcePath); /* the FMU has no resources */
    UNUSED(visible);
    UNUSED(requiredIntermediateVariables), UNUSED(intermediateUpdate);
    const fmu_logger logger = logger_of(instanceEnvironment, logMessage);
    if (eventModeUsed) {
        fmu_refuse_instantiation(&logger, __func__, instanceName,
                                 "eventModeUsed = true, but hasEventMode is false");
        return NULL;
    }
    if (nRequiredIntermediateVariables > 0) {
        fmu_refuse_instantiation(&logger, __func__, instanceName,
                                 "intermediate variables are required, but "
                                 "providesIntermediateUpdate is false");
        return NULL;
    }
    fmu_instance *inst = fmu_instantiate(3, __func__, instanceName, instantiationToken,
                                         FMU_INSTANTIATION_TOKEN, &logger, loggingOn);
    /* a step cut short by the work limit returns early if allowed, else is discarded */
    fmu_allow_early_return(inst, earlyReturnAllowed);
    return inst;
}

fmi3Instance fmi3InstantiateScheduledExecution(fmi3String instanceName,
                                               fmi3String instantiationToken,
                                               fmi3String resourcePath, fmi3Boolean visible,
                                               fmi3Boolean loggingOn,
                                               fmi3InstanceEnvironment instanceEnvironment,
                                               fmi3LogMessageCallback logMessage,
                                               fmi3ClockUpdateCallback clockUpdate,
                                               fmi3LockPreemptionCallback lockPreemption,
                                               fmi3UnlockPreemptionCallback unlockPreemption)
{
    UNUSED(instantiationToken), UNUSED(resourcePath), UNUSED(visible), UNUSED(loggingOn);
    UNUSED(clockUpdate), UNUSED(lockPreemption), UNUSED(unlockPreemption);
    const fmu_logger logger = logger_of(instanceEnvironment, logMessage);
    fmu_refuse_instantiation(&logger, __func__, instanceName,
                             "this FMU implements co-simulation only");
    return NULL;
}

void fmi3FreeInstance(fmi3Instance instance) { fmu_free(INST(instance)); }

fmi3Status fmi3EnterInitializationMode(fmi3Instance instance, fmi3Boolean toleranceDefined,
                                       fmi3Float64 tolerance, fmi3Float64 startTime,
                                       fmi3Boolean stopTimeDefined, fmi3Float64 stopTime)
{
    /* FMI 3.0 gives the experiment on entering Initialization Mode */
    const fmu_status st = fmu_setup_experiment(INST(instance), __func__, toleranceDefined,
                                               tolerance, startTime, stopTimeDefined, stopTime);
    return STATUS(st == FMU_OK ? fmu_enter_initialization(INST(instance), __func__) : st);
}

fmi3Status fmi3ExitInitializationMode(fmi3Instance instance)
{
    return STATUS(fmu_exit_initialization(INST(instance), __func__));
}

fmi3Status fmi3EnterEventMode(fmi3Instance instance)
{
    return STATUS(fmu_refuse(INST(instance), __func__, "hasEventMode is false"));
}

fmi3Status fmi3Terminate(fmi3Instance instance)
{
    return STATUS(fmu_terminate(INST(instance), __func__));
}

fmi3Status fmi3Reset(fmi3Instance instance) { return STATUS(fmu_reset(INST(instance), __func__)); }

/* ---- values ---------------------------------------------------------------------- */

#define GETTER(name, c_type_of_fmi, types, c_type)                                             \
    fmi3Status name(fmi3Instance instance, const fmi3ValueReference valueReferences[],         \
                    size_t nValueReferences, c_type_of_fmi values[], size_t nValues)           \
    {                                                                                          \
        return STATUS(fmu_get(INST(instance), __func__, types, c_type, valueReferences,        \
                              nValueReferences, values, nValues));                             \
    }
#define SETTER(name, c_type_of_fmi, types, c_type)                                             \
    fmi3Status name(fmi3Instance instance, const fmi3ValueReference valueReferences[],         \
                    size_t nValueReferences, const c_type_of_fmi values[], size_t nValues)     \
    {                                                                                          \
        return STATUS(fmu_set(INST(instance), __func__, types, c_type, valueReferences,        \
                              nValueReferences, values, nValues));                             \
    }

/* The types this FMU has variables of (FMI 3.0 accesses enumerations as Int64)... */
GETTER(fmi3GetFloat64, fmi3Float64, FMU_TYPE_BIT(FMU_TYPE_REAL), FMU_C_DOUBLE)
GETTER(fmi3GetInt32, fmi3Int32, FMU_TYPE_BIT(FMU_TYPE_INTEGER), FMU_C_INT32)
GETTER(fmi3GetUInt64, fmi3UInt64, FMU_TYPE_BIT(FMU_TYPE_COUNT), FMU_C_UINT64)
GETTER(fmi3GetInt64, fmi3Int64, FMU_TYPE_BIT(FMU_TYPE_ENUMERATION), FMU_C_INT64)
GETTER(fmi3GetBoolean, fmi3Boolean, FMU_TYPE_BIT(FMU_TYPE_BOOLEAN), FMU_C_BOOL)
SETTER(fmi3SetFloat64, fmi3Float64, FMU_TYPE_BIT(FMU_TYPE_REAL), FMU_C_DOUBLE)
SETTER(fmi3SetInt32, fmi3Int32, FMU_TYPE_BIT(FMU_TYPE_INTEGER), FMU_C_INT32)
SETTER(fmi3SetUInt64, fmi3UInt64, FMU_TYPE_BIT(FMU_TYPE_COUNT), FMU_C_UINT64)
SETTER(fmi3SetInt64, fmi3Int64, FMU_TYPE_BIT(FMU_TYPE_ENUMERATION), FMU_C_INT64)
SETTER(fmi3SetBoolean, fmi3Boolean, FMU_TYPE_BIT(FMU_TYPE_BOOLEAN), FMU_C_BOOL)

/* ...and those it has none of: every value reference is refused with its real type. */
GETTER(fmi3GetFloat32, fmi3Float32, 0, FMU_C_NONE)
GETTER(fmi3GetInt8, fmi3Int8, 0, FMU_C_NONE)
GETTER(fmi3GetUInt8, fmi3UInt8, 0, FMU_C_NONE)
GETTER(fmi3GetInt16, fmi3Int16, 0, FMU_C_NONE)
GETTER(fmi3GetUInt16, fmi3UInt16, 0, FMU_C_NONE)
GETTER(fmi3GetUInt32, fmi3UInt32, 0, FMU_C_NONE)
GETTER(fmi3GetString, fmi3String, 0, FMU_C_NONE)
SETTER(fmi3SetFloat32, fmi3Float32, 0, FMU_C_NONE)
SETTER(fmi3SetInt8, fmi3Int8, 0, FMU_C_NONE)
SETTER(fmi3SetUInt8, fmi3UInt8, 0, FMU_C_NONE)
SETTER(fmi3SetInt16, fmi3Int16, 0, FMU_C_NONE)
SETTER(fmi3SetUInt16, fmi3UInt16, 0, FMU_C_NONE)
SETTER(fmi3SetUInt32, fmi3UInt32, 0, FMU_C_NONE)
SETTER(fmi3SetString, fmi3String, 0, FMU_C_NONE)

fmi3Status fmi3GetBinary(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                         size_t nValueReferences, size_t valueSizes[], fmi3Binary values[],
                         size_t nValues)
{
    UNUSED(valueSizes);
    return STATUS(fmu_get(INST(instance), __func__, 0, FMU_C_NONE, valueReferences,
                          nValueReferences, values, nValues));
}

fmi3Status fmi3SetBinary(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                         size_t nValueReferences, const size_t valueSizes[],
                         const fmi3Binary values[], size_t nValues)
{
    UNUSED(valueSizes);
    return STATUS(fmu_set(INST(instance), __func__, 0, FMU_C_NONE, valueReferences,
                          nValueReferences, values, nValues));
}

fmi3Status fmi3GetClock(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                        size_t nValueReferences, fmi3Clock values[])
{
    return STATUS(fmu_get(INST(instance), __func__, 0, FMU_C_NONE, valueReferences,
                          nValueReferences, values, nValueReferences));
}

fmi3Status fmi3SetClock(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                        size_t nValueReferences, const fmi3Clock values[])
{
    return STATUS(fmu_set(INST(instance), __func__, 0, FMU_C_NONE, valueReferences,
                          nValueReferences, values, nValueReferences));
}

/* ---- dependencies and derivatives: not provided ------------------------------------ */

fmi3Status fmi3GetNumberOfVariableDependencies(fmi3Instance instance,
                                               fmi3ValueReference valueReference,
                                               size_t *nDependencies)
{
    UNUSED(valueReference), UNUSED(nDependencies);
    return STATUS(fmu_refuse(INST(instance), __func__, "providesPerElementDependencies is false"));
}

fmi3Status fmi3GetVariableDependencies(fmi3Instance instance, fmi3ValueReference dependent,
                                       size_t elementIndicesOfDependent[],
                                       fmi3ValueReference independents[],
                                       size_t elementIndicesOfIndependents[],
                                       fmi3DependencyKind dependencyKinds[], size_t nDependencies)
{
    UNUSED(dependent), UNUSED(elementIndicesOfDependent), UNUSED(independents);
    UNUSED(elementIndicesOfIndependents), UNUSED(dependencyKinds), UNUSED(nDependencies);
    return STATUS(fmu_refuse(INST(instance), __func__, "providesPerElementDependencies is false"));
}

fmi3Status fmi3GetDirectionalDerivative(fmi3Instance instance, const fmi3ValueReference unknowns[],
                                        size_t nUnknowns, const fmi3ValueReference knowns[],
                                        size_t nKnowns, const fmi3Float64 seed[], size_t nSeed,
                                        fmi3Float64 sensitivity[], size_t nSensitivity)
{
    UNUSED(unknowns), UNUSED(nUnknowns), UNUSED(knowns), UNUSED(nKnowns), UNUSED(seed);
    UNUSED(nSeed), UNUSED(sensitivity), UNUSED(nSensitivity);
    return STATUS(fmu_refuse(INST(instance), __func__, "providesDirectionalDerivatives is false"));
}

fmi3Status fmi3GetAdjointDerivative(fmi3Instance instance, const fmi3ValueReference unknowns[],
                                    size_t nUnknowns, const fmi3ValueReference knowns[],
                                    size_t nKnowns, const fmi3Float64 seed[], size_t nSeed,
                                    fmi3Float64 sensitivity[], size_t nSensitivity)
{
    UNUSED(unknowns), UNUSED(nUnknowns), UNUSED(knowns), UNUSED(nKnowns), UNUSED(seed);
    UNUSED(nSeed), UNUSED(sensitivity), UNUSED(nSensitivity);
    return STATUS(fmu_refuse(INST(instance), __func__, "providesAdjointDerivatives is false"));
}

/* ---- FMU states ------------------------------------------------------------------ */

fmi3Status fmi3GetFMUState(fmi3Instance instance, fmi3FMUState *FMUState)
{
    fmu_state *s = FMUState ? *FMUState : NULL;
    const fmu_status st = fmu_state_get(INST(instance), __func__, FMUState ? &s : NULL);
    if (FMUState)
        *FMUState = s;
    return STATUS(st);
}

fmi3Status fmi3SetFMUState(fmi3Instance instance, fmi3FMUState FMUState)
{
    return STATUS(fmu_state_set(INST(instance), __func__, FMUState));
}

fmi3Status fmi3FreeFMUState(fmi3Instance instance, fmi3FMUState *FMUState)
{
    fmu_state *s = FMUState ? *FMUState : NULL;
    const fmu_status st = fmu_state_free(INST(instance), __func__, &s);
    if (FMUState)
        *FMUState = s;
    return STATUS(st);
}

fmi3Status fmi3SerializedFMUStateSize(fmi3Instance instance, fmi3FMUState FMUState, size_t *size)
{
    return STATUS(fmu_state_size(INST(instance), __func__, FMUState, size));
}

fmi3Status fmi3SerializeFMUState(fmi3Instance instance, fmi3FMUState FMUState,
                                 fmi3Byte serializedState[], size_t size)
{
    return STATUS(fmu_state_serialize(INST(instance), __func__, FMUState, serializedState, size));
}

fmi3Status fmi3DeserializeFMUState(fmi3Instance instance, const fmi3Byte serializedState[],
                                   size_t size, fmi3FMUState *FMUState)
{
    fmu_state *s = NULL;
    const fmu_status st = fmu_state_deserialize(INST(instance), __func__, serializedState, size,
                                                FMUState ? &s : NULL);
    if (FMUState && st == FMU_OK)
        *FMUState = s;
    return STATUS(st);
}

/* ---- Configuration Mode: where the structural parameter n_segments is set -------- */

fmi3Status fmi3EnterConfigurationMode(fmi3Instance instance)
{
    return STATUS(fmu_enter_configuration(INST(instance), __func__));
}

fmi3Status fmi3ExitConfigurationMode(fmi3Instance instance)
{
    return STATUS(fmu_exit_configuration(INST(instance), __func__));
}

/* ---- clocks and event mode: this FMU has neither -------------------------------- */

#define NO_CLOCKS "this FMU has no clocks"

fmi3Status fmi3GetIntervalDecimal(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                                  size_t nValueReferences, fmi3Float64 intervals[],
                                  fmi3IntervalQualifier qualifiers[])
{
    UNUSED(valueReferences), UNUSED(nValueReferences), UNUSED(intervals), UNUSED(qualifiers);
    return STATUS(fmu_refuse(INST(instance), __func__, NO_CLOCKS));
}

fmi3Status fmi3GetIntervalFraction(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                                   size_t nValueReferences, fmi3UInt64 counters[],
                                   fmi3UInt64 resolutions[], fmi3IntervalQualifier qualifiers[])
{
    UNUSED(valueReferences), UNUSED(nValueReferences), UNUSED(counters), UNUSED(resolutions);
    UNUSED(qualifiers);
    return STATUS(fmu_refuse(INST(instance), __func__, NO_CLOCKS));
}

fmi3Status fmi3GetShiftDecimal(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                               size_t nValueReferences, fmi3Float64 shifts[])
{
    UNUSED(valueReferences), UNUSED(nValueReferences), UNUSED(shifts);
    return STATUS(fmu_refuse(INST(instance), __func__, NO_CLOCKS));
}

fmi3Status fmi3GetShiftFraction(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                                size_t nValueReferences, fmi3UInt64 counters[],
                                fmi3UInt64 resolutions[])
{
    UNUSED(valueReferences), UNUSED(nValueReferences), UNUSED(counters), UNUSED(resolutions);
    return STATUS(fmu_refuse(INST(instance), __func__, NO_CLOCKS));
}

fmi3Status fmi3SetIntervalDecimal(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                                  size_t nValueReferences, const fmi3Float64 intervals[])
{
    UNUSED(valueReferences), UNUSED(nValueReferences), UNUSED(intervals);
    return STATUS(fmu_refuse(INST(instance), __func__, NO_CLOCKS));
}

fmi3Status fmi3SetIntervalFraction(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                                   size_t nValueReferences, const fmi3UInt64 counters[],
                                   const fmi3UInt64 resolutions[])
{
    UNUSED(valueReferences), UNUSED(nValueReferences), UNUSED(counters), UNUSED(resolutions);
    return STATUS(fmu_refuse(INST(instance), __func__, NO_CLOCKS));
}

fmi3Status fmi3SetShiftDecimal(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                               size_t nValueReferences, const fmi3Float64 shifts[])
{
    UNUSED(valueReferences), UNUSED(nValueReferences), UNUSED(shifts);
    return STATUS(fmu_refuse(INST(instance), __func__, NO_CLOCKS));
}

fmi3Status fmi3SetShiftFraction(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                                size_t nValueReferences, const fmi3UInt64 counters[],
                                const fmi3UInt64 resolutions[])
{
    UNUSED(valueReferences), UNUSED(nValueReferences), UNUSED(counters), UNUSED(resolutions);
    return STATUS(fmu_refuse(INST(instance), __func__, NO_CLOCKS));
}

fmi3Status fmi3EvaluateDiscreteStates(fmi3Instance instance)
{
    return STATUS(fmu_refuse(INST(instance), __func__, "hasEventMode is false"));
}

fmi3Status fmi3UpdateDiscreteStates(fmi3Instance instance, fmi3Boolean *discreteStatesNeedUpdate,
                                    fmi3Boolean *terminateSimulation,
                                    fmi3Boolean *nominalsOfContinuousStatesChanged,
                                    fmi3Boolean *valuesOfContinuousStatesChanged,
                                    fmi3Boolean *nextEventTimeDefined, fmi3Float64 *nextEventTime)
{
    UNUSED(discreteStatesNeedUpdate), UNUSED(terminateSimulation);
    UNUSED(nominalsOfContinuousStatesChanged), UNUSED(valuesOfContinuousStatesChanged);
    UNUSED(nextEventTimeDefined), UNUSED(nextEventTime);
    return STATUS(fmu_refuse(INST(instance), __func__, "hasEventMode is false"));
}

/* ---- model exchange: not implemented ------------------------------------------ */

#define NOT_MODEL_EXCHANGE "this FMU implements co-simulation only"

fmi3Status fmi3EnterContinuousTimeMode(fmi3Instance instance)
{
    return STATUS(fmu_refuse(INST(instance), __func__, NOT_MODEL_EXCHANGE));
}

fmi3Status fmi3CompletedIntegratorStep(fmi3Instance instance,
                                       fmi3Boolean noSetFMUStatePriorToCurrentPoint,
                                       fmi3Boolean *enterEventMode,
                                       fmi3Boolean *terminateSimulation)
{
    UNUSED(noSetFMUStatePriorToCurrentPoint), UNUSED(enterEventMode), UNUSED(terminateSimulation);
    return STATUS(fmu_refuse(INST(instance), __func__, NOT_MODEL_EXCHANGE));
}

fmi3Status fmi3SetTime(fmi3Instance instance, fmi3Float64 time)
{
    UNUSED(time);
    return STATUS(fmu_refuse(INST(instance), __func__, NOT_MODEL_EXCHANGE));
}

fmi3Status fmi3SetContinuousStates(fmi3Instance instance, const fmi3Float64 continuousStates[],
                                   size_t nContinuousStates)
{
    UNUSED(continuousStates), UNUSED(nContinuousStates);
    return STATUS(fmu_refuse(INST(instance), __func__, NOT_MODEL_EXCHANGE));
}

fmi3Status fmi3GetContinuousStateDerivatives(fmi3Instance instance, fmi3Float64 derivatives[],
                                             size_t nContinuousStates)
{
    UNUSED(derivatives), UNUSED(nContinuousStates);
    return STATUS(fmu_refuse(INST(instance), __func__, NOT_MODEL_EXCHANGE));
}

fmi3Status fmi3GetEventIndicators(fmi3Instance instance, fmi3Float64 eventIndicators[],
                                  size_t nEventIndicators)
{
    UNUSED(eventIndicators), UNUSED(nEventIndicators);
    return STATUS(fmu_refuse(INST(instance), __func__, NOT_MODEL_EXCHANGE));
}

fmi3Status fmi3GetContinuousStates(fmi3Instance instance, fmi3Float64 continuousStates[],
                                   size_t nContinuousStates)
{
    UNUSED(continuousStates), UNUSED(nContinuousStates);
    return STATUS(fmu_refuse(INST(instance), __func__, NOT_MODEL_EXCHANGE));
}

fmi3Status fmi3GetNominalsOfContinuousStates(fmi3Instance instance, fmi3Float64 nominals[],
                                             size_t nContinuousStates)
{
    UNUSED(nominals), UNUSED(nContinuousStates);
    return STATUS(fmu_refuse(INST(instance), __func__, NOT_MODEL_EXCHANGE));
}

fmi3Status fmi3GetNumberOfEventIndicators(fmi3Instance instance, size_t *nEventIndicators)
{
    UNUSED(nEventIndicators);
    return STATUS(fmu_refuse(INST(instance), __func__, NOT_MODEL_EXCHANGE));
}

fmi3Status fmi3GetNumberOfContinuousStates(fmi3Instance instance, size_t *nContinuousStates)
{
    UNUSED(nContinuousStates);
    return STATUS(fmu_refuse(INST(instance), __func__, NOT_MODEL_EXCHANGE));
}

/* ---- co-simulation ------------------------------------------------------------------ */

fmi3Status fmi3EnterStepMode(fmi3Instance instance)
{
    return STATUS(fmu_refuse(INST(instance), __func__,
                             "Step Mode follows Initialization Mode directly: hasEventMode is false"));
}

fmi3Status fmi3GetOutputDerivatives(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                                    size_t nValueReferences, const fmi3Int32 orders[],
                                    fmi3Float64 values[], size_t nValues)
{
    UNUSED(valueReferences), UNUSED(nValueReferences), UNUSED(orders), UNUSED(values);
    UNUSED(nValues);
    return STATUS(fmu_refuse(INST(instance), __func__, "maxOutputDerivativeOrder is 0"));
}

fmi3Status fmi3DoStep(fmi3Instance instance, fmi3Float64 currentCommunicationPoint,
                      fmi3Float64 communicationStepSize,
                      fmi3Boolean noSetFMUStatePriorToCurrentPoint,
                      fmi3Boolean *eventHandlingNeeded, fmi3Boolean *terminateSimulation,
                      fmi3Boolean *earlyReturn, fmi3Float64 *lastSuccessfulTime)
{
    UNUSED(noSetFMUStatePriorToCurrentPoint); /* states cost nothing to keep */
    double reached = 0.0;
    int early_return = 0, terminate = 0;
    const fmu_status st = fmu_do_step(INST(instance), __func__, currentCommunicationPoint,
                                      communicationStepSize, &reached, &early_return, &terminate);
    if (eventHandlingNeeded)
        *eventHandlingNeeded = fmi3False;
    if (terminateSimulation)
        *terminateSimulation = terminate ? fmi3True : fmi3False;
    if (earlyReturn)
        *earlyReturn = early_return ? fmi3True : fmi3False;
    if (lastSuccessfulTime)
        *lastSuccessfulTime = reached;
    return STATUS(st);
}

/* ---- scheduled execution: not implemented --------------------------------------- */

fmi3Status fmi3ActivateModelPartition(fmi3Instance instance, fmi3ValueReference clockReference,
                                      fmi3Float64 activationTime)
{
    UNUSED(clockReference), UNUSED(activationTime);
    return STATUS(fmu_refuse(INST(instance), __func__, "this FMU implements co-simulation only"));
}
